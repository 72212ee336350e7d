import os
from setuptools import setup

package_name = 'gripper_unread'
data_files = [('share/' + package_name, ['package.xml'])]
# built by walking folders: not read without running setup.py
for folder, _, names in os.walk('generated'):
    data_files.append((os.path.join('share', package_name, folder), [os.path.join(folder, n) for n in names]))

setup(name=package_name, data_files=data_files)
