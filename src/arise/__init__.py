"""arise: natural-language traffic scenarios to executable Scenic 3 scripts."""

__version__ = "0.1.0"
