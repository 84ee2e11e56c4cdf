"""impactbench's report: figures and tables from a suite's saved results (runs.csv and the run folders)."""
