"""Driving agents under test: `arise drive`, its metrics, store, runner and report."""
