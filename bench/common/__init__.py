"""What the benchmarks share: where things are (paths), the chain most of
them run (chain), reading a time off a work-precision curve (time_to),
timing loops (timing), what a result records of the run (record) and what
they take from tests/ and examples/ (repo)."""
