import os
from glob import glob
from setuptools import setup

package_name = 'hand_py'

data_files = [('share/ament_index/resource_index/packages', ['resource/' + package_name])]
data_files += [(os.path.join('share', package_name, 'meshes'), glob('models/meshes/*.stl'))]

setup(
    name=package_name,
    version='0.0.1',
    packages=[package_name],
    data_files=data_files + [('share/' + package_name + '/urdf', ['description/hand.xacro'])],
)
