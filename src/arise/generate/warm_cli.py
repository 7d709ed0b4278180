"""``arise llm warm``: build the prefix store for the embedded model ahead of time.

A first ``arise generate`` builds the store by itself; this command does it up front (for
an image, or before a benchmark) and shows what is stored, or clears it.
"""

from __future__ import annotations

from typing import Annotated

import typer

from arise import terminal
from arise.generate.prefixes import fixed_prefixes
from arise.llm.types import LLMError, PrefixUse

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
    from arise.llm.local import LocalProvider
    from arise.llm.registry import get_provider

    llm = get_provider("local", cache=False, model_path=model_path)
    backend = llm.unwrap()
    if not isinstance(backend, LocalProvider):  # a config that redefines "local"
        raise LLMError("the prefix store is for the embedded model (kind = local)")
    store = backend.store
    if store is None:
        raise LLMError("the prefix store is off (ARISE_PREFIX_STORE=off or prefix_store = false)")
    if clear:
        removed = store.clear()
        console.print(
            terminal.text(f"removed {removed} stored prefix(es) from ", terminal.name(store.root))
        )
        return
    with console.status("evaluating the fixed prompt prefixes..."):
        outcomes = backend.warm(fixed_prefixes())
    for name, outcome in outcomes.items():
        console.print(
            terminal.text(
                f"{name}: {outcome.tokens} tokens, {_SAID[outcome.use]} ({outcome.seconds:.1f} s)"
            )
        )
    for note in store.discarded:
        console.print(terminal.text(("rebuilt", "yellow"), " ", note))
    console.print(terminal.text("store: ", store.describe()))
