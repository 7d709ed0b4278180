"""``arise llm warm``: build the prefix store for the embedded model ahead of time.

A first ``arise generate`` builds the store by itself; this command does it up front (for
an image, or before a benchmark) and shows what is stored, or clears it.
"""

from __future__ import annotations

from typing import Annotated

import typer

from arise import terminal
from arise.generate.warm import clear_prefixes, warm_prefixes
from arise.llm.types import PrefixUse

WARM_HELP = (
    "Evaluate the fixed prompt prefixes (system prompts, examples) of the generator's "
    "model calls once and keep the embedded model's state after each on disk, so every "
    "later process skips them. `arise generate` does this by itself on its first run.\n\n"
    "Example: arise llm warm        (build what is missing)\n\n"
    "Example: arise llm warm --clear (delete the store)"
)

console = terminal.console()

_SAID = {
    PrefixUse.BUILT: "built and stored",
    PrefixUse.LOADED: "already stored",
    PrefixUse.IN_CONTEXT: "already stored",
    PrefixUse.EVALUATED: "evaluated, but the store is off or not writable",
    PrefixUse.NONE: "not split (the chat template cannot render it apart)",
}


def warm_command(
    model_path: Annotated[
        str | None, typer.Option(help="GGUF file (default: the embedded model).")
    ] = None,
    clear: Annotated[bool, typer.Option("--clear", help="Delete every stored prefix.")] = False,
) -> None:
    if clear:
        removed, root = clear_prefixes(model_path)
        console.print(
            terminal.text(f"removed {removed} stored prefix(es) from ", terminal.name(root))
        )
        return
    with console.status("evaluating the fixed prompt prefixes..."):
        warmed = warm_prefixes(model_path)  # LLMError: one line, exit 1
    for name, outcome in warmed.outcomes.items():
        console.print(
            terminal.text(
                f"{name}: {outcome.tokens} tokens, {_SAID[outcome.use]} ({outcome.seconds:.1f} s)"
            )
        )
    for note in warmed.discarded:
        console.print(terminal.text(("rebuilt", "yellow"), " ", note))
    console.print(terminal.text("store: ", warmed.store))
