"""impactbench compare: two result folders side by side (reports/compare.py)."""
