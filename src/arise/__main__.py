"""`python -m arise` is the same as the `arise` command."""

from arise.cli import main

main()
