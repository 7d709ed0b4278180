"""The language layer: a description is read once, here, into typed values.

`read_cast` finds who and what the text names (the ego under its many names, each other
road user or object, pronouns and "the other car" folded into the actor they mean);
`clauses` says whose each verb is; `rules` holds every reading rule as data, each with
example sentences and the facts they must give; `readers` and `actors` apply them per
actor (`weather` for weather, light and visibility), each fact a `facts.GroundedFact` with
the words it rests on; `examples.read_facts` is what the rules' examples are checked
against; `condense` trims a crash report to its scenario and `quotes` finds a quote in the
text. Stages after extraction consume the typed result and never read the description again.
"""
