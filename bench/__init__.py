"""lagmb's benchmarks (bench/README.md): importable as a package from the
repository root, so that the scripts share bench/common/ without path edits
of their own."""
