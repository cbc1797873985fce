"""lagmb against other engines on the same problems (bench/README.md)."""
