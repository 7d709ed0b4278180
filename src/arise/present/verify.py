"""Checks of an exported scenario.xosc: the OpenSCENARIO XSD, ASAM's checker, and a round
trip that reads the motion back.

The XSD comes from the installed scenariogeneration package and ASAM's checker from the
`asam-qc-openscenarioxml` package (a dev extra): neither is copied into arise.
"""

from __future__ import annotations

import logging
import math
import tempfile
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path

from arise.present.errors import PresentError
from arise.validate.types import AgentTrace


class CheckerMissing(PresentError):
    """A checker package is not installed (they come with arise's dev extra)."""


def xsd_path(minor: int = 2) -> Path:
    """OpenSCENARIO 1.`minor`'s schema as shipped by the scenariogeneration package."""
    wanted = f"OpenSCENARIO_1_{minor}.xsd"
    try:
        files = metadata.files("scenariogeneration") or []
    except metadata.PackageNotFoundError:
        raise CheckerMissing("scenariogeneration is not installed") from None
    for entry in files:
        if entry.name == wanted:
            return Path(str(entry.locate())).resolve()
    raise CheckerMissing(f"{wanted} is not in the installed scenariogeneration package")


def xsd_errors(xosc: Path, minor: int = 2) -> list[str]:
    """Schema violations of the file (empty: valid)."""
    from lxml import etree

    schema = etree.XMLSchema(etree.parse(str(xsd_path(minor))))
    document = etree.parse(str(xosc))
    if schema.validate(document):
        return []
    return [f"line {e.line}: {e.message}" for e in schema.error_log]


@dataclass
class CheckerReport:
    """ASAM's OpenSCENARIO XML checker bundle on one file."""

    issues: list[str] = field(default_factory=list)
    statuses: dict[str, str] = field(default_factory=dict)  # checker id -> completed/skipped/error

    @property
    def ok(self) -> bool:
        return not self.issues and "error" not in self.statuses.values()


def asam_check(xosc: Path) -> CheckerReport:
    """Run every check of ASAM's OpenSCENARIO XML checker bundle on the file."""
    try:
        from qc_baselib import Configuration, Result
        from qc_openscenario import constants
        from qc_openscenario.main import run_checks
    except ImportError:
        raise CheckerMissing(
            "ASAM's checker is not installed: pip install asam-qc-openscenarioxml "
            "(arise's dev extra)"
        ) from None
    config = Configuration()
    config.set_config_param("InputFile", str(xosc.resolve()))
    config.register_checker_bundle(constants.BUNDLE_NAME)
    result = Result()
    result.register_checker_bundle(
        name=constants.BUNDLE_NAME,
        description="OpenScenario checker bundle",
        version=constants.BUNDLE_VERSION,
        summary="",
    )
    result.set_result_version(version=constants.BUNDLE_VERSION)
    root = logging.getLogger()
    level = root.level
    root.setLevel(logging.WARNING)  # the bundle logs every check at INFO
    try:
        run_checks(config, result)
    finally:
        root.setLevel(level)
    report = CheckerReport()
    for checker in result.get_checker_results(constants.BUNDLE_NAME):
        status = checker.status.value if checker.status is not None else "none"
        report.statuses[checker.checker_id] = str(status)
        for issue in checker.issues:
            report.issues.append(f"{checker.checker_id}: {issue.description}")
    with tempfile.TemporaryDirectory() as folder:  # the bundle's own result file, as a check
        result.write_to_file(str(Path(folder) / "result.xqar"))
    return report


@dataclass
class ReadBack:
    """An agent's motion as read back from the file."""

    start: tuple[float, float, float]  # x, y, h of its TeleportAction
    speed: float | None
    times: list[float]
    points: list[tuple[float, float]]

    def at(self, t: float) -> tuple[float, float]:
        """Linear interpolation in time, as a player follows a timed polyline."""
        if not self.times:
            return self.start[0], self.start[1]
        if t <= self.times[0]:
            return self.points[0]
        for i in range(1, len(self.times)):
            if t <= self.times[i]:
                t0, t1 = self.times[i - 1], self.times[i]
                share = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
                (x0, y0), (x1, y1) = self.points[i - 1], self.points[i]
                return x0 + (x1 - x0) * share, y0 + (y1 - y0) * share
        return self.points[-1]


def read_back(xosc: Path) -> dict[str, ReadBack]:
    """Each entity's start, speed and timed trajectory vertices, parsed from the XML."""
    import xml.etree.ElementTree as ET

    root = ET.parse(xosc).getroot()
    found: dict[str, ReadBack] = {}
    for private in root.iter("Private"):
        name = private.get("entityRef", "")
        position = private.find(".//TeleportAction/Position/WorldPosition")
        speed = private.find(".//SpeedActionTarget/AbsoluteTargetSpeed")
        if position is None:
            continue
        found[name] = ReadBack(
            start=(
                float(position.get("x", 0)),
                float(position.get("y", 0)),
                float(position.get("h", 0)),
            ),
            speed=float(speed.get("value", 0)) if speed is not None else None,
            times=[],
            points=[],
        )
    for group in root.iter("ManeuverGroup"):
        actor = group.find("Actors/EntityRef")
        if actor is None or actor.get("entityRef") not in found:
            continue
        motion = found[actor.get("entityRef", "")]
        for vertex in group.iter("Vertex"):
            position = vertex.find("Position/WorldPosition")
            if position is None:
                continue
            motion.times.append(float(vertex.get("time", 0)))
            motion.points.append((float(position.get("x", 0)), float(position.get("y", 0))))
    return found


def worst_gap(agent: AgentTrace, motion: ReadBack, timestep: float) -> float:
    """The largest distance, over every step of the trace, between the trace and the
    motion the file describes at that time."""
    worst = 0.0
    for point in agent.trajectory:
        x, y = motion.at(point.step * timestep)
        worst = max(worst, math.hypot(x - point.x, y - point.y))
    return worst
