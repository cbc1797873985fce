"""What accuracy costs with each method: work-precision sweeps (bench/README.md)."""
