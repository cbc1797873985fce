"""How the cost of lagmb's calls grows and where it goes (bench/README.md)."""
