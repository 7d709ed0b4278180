"""Evaluation: benchmark runs, the paper's metrics, judges and reports."""
