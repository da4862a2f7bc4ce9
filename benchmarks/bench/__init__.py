"""The benchmark suite's parts: running mixtrace (mixtrace.py), cached references
(references.py), reading PFM error maps (pfm.py), charts (plots.py) and tables (report.py).
benchmarks/suite.py puts them together."""
