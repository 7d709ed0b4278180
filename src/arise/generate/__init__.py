"""The generator: description -> ScenarioSpec -> retrieved snippets -> script -> test and repair."""
