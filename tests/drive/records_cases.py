"""Hand-built drive records with known metrics, for the store and report tests."""

from __future__ import annotations

from arise.drive.records import DriveRecord, DriveStatus, DriveTask

DIGEST = "ab" * 32


def task(scenario: str, category: str, run: int = 0, agent: str = "idm") -> DriveTask:
    return DriveTask(
        scenario=scenario,
        category=category,
        script=f"/scripts/{scenario}.scenic",
        digest=DIGEST,
        agent=agent,
        run_index=run,
        seed=run,
    )


def driven(
    scenario: str, category: str, run: int = 0, **metrics: float | int | None
) -> DriveRecord:
    values: dict[str, float | int | None] = {
        "collision": 0,
        "red_lights_run": 0,
        "stop_signs_run": 0,
        "out_of_road_m": 0.0,
        "distance_to_route_m": 0.5,
        "route_following": 0.9,
        "route_completion": 1.0,
        "time_spent_s": 10.0,
        "mean_acceleration": 1.0,
        "mean_yaw_velocity": 0.1,
        "lane_invasions": 0,
        "overall_score": 0.9,
        "min_ttc_s": None,
        "conflict_reached": 1,
    }
    values.update(metrics)
    return DriveRecord(
        task=task(scenario, category, run),
        status=DriveStatus.DRIVEN,
        metrics=values,
        seconds=1.5,
        sandbox="landlock+seccomp+rlimits",
        map="arise_straight",
        timeout_s=30.0,
        replay=f"collisions/{scenario}-idm-r{run}/replay.gif" if values["collision"] else None,
    )


def failed(scenario: str, category: str, message: str) -> DriveRecord:
    return DriveRecord(
        task=task(scenario, category),
        status=DriveStatus.FAILED,
        message=message,
        sandbox="landlock+seccomp+rlimits",
    )
