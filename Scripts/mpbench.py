"""What the benchmark scripts share: the filter timed on a pair, as the README reports it."""
import time


def best_run(target, source, threads, repeats):
    """The best of `repeats` fresh runs of the filter on `threads` threads:
    (seconds, input, neighbours, search, solve, pieces)."""
    import meshprojection
    best = None
    for _ in range(repeats):
        f = meshprojection.vtkMeshProjectionFilter()
        f.SetInputData(target)
        f.SetSourceData(source)
        f.SetNumberOfThreads(threads)
        f.SetCacheOperator(False)
        start = time.perf_counter()
        f.Update()
        seconds = time.perf_counter() - start
        if best is None or seconds < best[0]:
            best = (seconds, f.GetInputTime(), f.GetNeighborsTime(), f.GetSearchTime(), f.GetSolveTime(),
                    f.GetNumberOfIntersections())
    return best


def time_filter(target, source, threads=(1, 2), repeats=2):
    """Prints the best of `repeats` runs of the filter on each thread count,
    with its stages (input, neighbours, search, solve) and pieces."""
    for count in threads:
        print("%d thread(s): %.3f s (input %.3f, neighbours %.3f, search %.3f, solve %.3f), %d pieces" %
              ((count,) + best_run(target, source, count, repeats)))
