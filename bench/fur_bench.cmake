# bench_fur: per-frame fur generation on the default monkey (issue 3 targets: 500k polylines
# <= 4 ms, 500k lines <= 2 ms per frame on 2 threads).
pelage_bench(bench_fur SOURCES fur_bench.cpp LIBS pelage::fur pelage::skin pelage::models)
