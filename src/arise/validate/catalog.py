"""The CARLA blueprints of the installed CARLA version, by category (`arise blueprints`)."""

from __future__ import annotations

from arise.errors import AriseError


class UnknownCategory(AriseError):
    """A blueprint category the installed CARLA version does not have."""


def blueprint_categories() -> dict[str, list[str]]:
    """Every category (car, truck, walker, ...) with its blueprints, sorted by category."""
    import scenic.simulators.carla.blueprints as table

    found = {
        name.removesuffix("Models"): list(getattr(table, name))
        for name in dir(table)
        if name.endswith("Models") and isinstance(getattr(table, name), list)
    }
    return dict(sorted(found.items()))


def blueprints(category: str | None = None) -> dict[str, list[str]]:
    """The blueprints of one category, or of all of them when `category` is None."""
    categories = blueprint_categories()
    if category is None:
        return categories
    if category not in categories:
        raise UnknownCategory(f"unknown category {category!r}; choose from {', '.join(categories)}")
    return {category: categories[category]}
