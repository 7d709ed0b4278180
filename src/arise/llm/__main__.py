"""``python -m arise.llm ...``: the LLM commands without the rest of the CLI (used by make)."""

from arise.llm.cli import main

main()
