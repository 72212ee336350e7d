import sys, cProfile, pstats, time
sys.path.insert(0, '.')
from benchmarks.bench_check import corpus_urdfs
files = [str(p) for p in corpus_urdfs()]
from urdftool.lint.runner import check_paths
import urdftool.lint.engine
pr = cProfile.Profile()
t=time.process_time()
prof = sys.argv[1:2]==["prof"]
if prof: pr.enable()
run = check_paths(files, jobs=1, timeout=0, max_memory=0)
if prof: pr.disable()
print("cpu", time.process_time()-t, len(run.results), sum(len(r.findings) for r in run.results), file=sys.stderr)
if prof:
    st = pstats.Stats(pr, stream=sys.stderr)
    st.sort_stats("tottime").print_stats(45)
    st.sort_stats("cumulative").print_stats(90)
