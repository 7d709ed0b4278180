"""Write broken variants of the base script (dev helper, run once)."""

from pathlib import Path

base = Path("/work/main/tests/data/base_crossing.scenic").read_text()
out = Path("/work/main/tests/data/broken")


def sub(old, new, count=1):
    assert old in base, old
    return base.replace(old, new, count)


variants = {
    "scenic2_no_new": sub("ego = new Car at EgoSpawnPt", "ego = Car at EgoSpawnPt"),
    "indentation": sub(
        "    while True:\n        take SetWalkingSpeedAction(0)",
        "    while True:\n    take SetWalkingSpeedAction(0)",
    ),
    "undefined_name_top": sub(
        "with behavior AdversaryBehavior()", "with behavior AdversaryBehaviour()"
    ),
    "undefined_name_behavior": sub(
        "    do CrossingBehavior(ego, globalParameters.OPT_ADV_SPEED, globalParameters.OPT_TRIGGER) until (distance from self to ego) < 4",
        "    take SetWalkingSpeedAktion(0)",
    ),
    "wrong_specifier": sub(
        "ego = new Car at EgoSpawnPt,", "ego = new Car at EgoSpawnPt, ahead of EgoSpawnPt by 5,"
    ),
    "unknown_blueprint": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"', 'EGO_MODEL = "vehicle.lincoln.mkz2017"'
    ),
    "unsatisfiable_requirement": sub(
        "require (distance to intersection) > 30", "require (distance to AdvAgent) > 500"
    ),
    "overlapping_spawn": sub(
        "AdvAgent = new Pedestrian right of AdvSpawnPt by 4",
        "AdvAgent = new Pedestrian at EgoSpawnPt",
    ),
    "violated_in_simulation": sub(
        "terminate when (distance to EgoSpawnPt) > 60",
        "require eventually ego.speed > 20\nterminate when (distance to EgoSpawnPt) > 60",
    ),
    "infinite_loop_behavior": sub(
        "    do CrossingBehavior(ego, globalParameters.OPT_ADV_SPEED, globalParameters.OPT_TRIGGER) until (distance from self to ego) < 4"
        + "\n    while True:\n        take SetWalkingSpeedAction(0)",
        "    while True:\n        speed = 0\n    take SetWalkingSpeedAction(0)",
    ),
    "infinite_loop_top": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"\nwhile True:\n    pass',
    ),
    "memory_bomb": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"\nballast = [0] * (10 ** 10)',
    ),
    "forbidden_import": sub(
        "model scenic.simulators.carla.model", "model scenic.simulators.carla.model\nimport os"
    ),
    "file_write": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"\nopen("/tmp/arise-pwned", "w").write("x")',
    ),
    "dunder_escape": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"\nescape = ().__class__.__bases__[0].__subclasses__()',
    ),
    "wrong_model": sub(
        "model scenic.simulators.carla.model", "model scenic.simulators.carla.modle"
    ),
    "bad_weather": sub("param weather = 'ClearNoon'", "param weather = 'SunnyNoon'"),
    "type_error_top": sub(
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
        'EGO_MODEL = "vehicle.lincoln.mkz_2017"\nEGO_SPEED = 8 + "m/s"',
    ),
    "attribute_error_behavior": sub(
        "    do CrossingBehavior(ego, globalParameters.OPT_ADV_SPEED, globalParameters.OPT_TRIGGER) until (distance from self to ego) < 4",
        "    take SetWalkingSpeedAction(self.velocityy)",
    ),
    "no_ego": sub("ego = new Car at EgoSpawnPt,", "egoCar = new Car at EgoSpawnPt,")
    .replace("(ego,", "(egoCar,")
    .replace("to ego)", "to egoCar)"),
    "unclosed_paren": sub(
        "require (distance to intersection) > 30", "require (distance to intersection > 30"
    ),
}
for name, text in variants.items():
    (out / f"{name}.scenic").write_text(text)
print(len(variants))
