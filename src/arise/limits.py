"""Every bound on data the parent did not make itself, in one place.

A worker's result, a run folder's trace.json and report.json, and a map file next to a
script are untrusted input: a script may forge its result line, and a run folder may come
from anyone. The schemas (`arise.validate.types`, `arise.present.tracefile`) and the map
cache (`arise.maps.cache`) refuse anything past these bounds instead of trusting it.
Generous for real runs (a few dozen agents, a few thousand steps), small enough that a
replay or an export of the largest accepted trace still finishes.
"""

from __future__ import annotations

# --- traces ------------------------------------------------------------------------------
#: Agents in one simulation.
MAX_AGENTS = 256
#: Steps of one simulation, so points of one agent's trajectory (steps + 1).
MAX_STEPS = 20_000
MAX_TRACE_POINTS = MAX_STEPS + 1
#: Trajectory points of all agents together (e.g. 256 agents x 1,950 steps).
MAX_TOTAL_POINTS = 500_000
#: Recorded world events (light changes, gear shifts, ...).
MAX_EVENTS = 10_000
#: Keys of one event, and items of a list value in it.
MAX_EVENT_FIELDS = 16
MAX_EVENT_LIST = 256
#: Scene parameters kept with a trace (weather, OPT_* values, ...).
MAX_PARAMS = 256
#: Any coordinate, length or speed: metres, m/s; far beyond any map.
MAX_MAGNITUDE = 1e7
#: Seconds per simulation step.
MAX_TIMESTEP = 10.0

# --- text --------------------------------------------------------------------------------
#: A diagnostic's message, hint or excerpt.
MAX_MESSAGE = 64 * 1024
#: A warning, a note, a scene parameter's value, a termination reason.
MAX_NOTE = 4096
#: A name: an agent, a class, a blueprint, an error type, a section, a parameter.
MAX_NAME = 256
#: Warnings and notes of one result; rejection reasons of one diagnostic.
MAX_WARNINGS = 64
MAX_REJECTIONS = 256
#: Timings of one result.
MAX_TIMINGS = 32
#: A path the parent chose (it is never read back from untrusted data).
MAX_PATH = 4096

# --- files -------------------------------------------------------------------------------
#: trace.json and report.json are refused above this size before they are read.
MAX_TRACE_FILE_BYTES = 64 * 1024 * 1024
MAX_REPORT_FILE_BYTES = 16 * 1024 * 1024
#: A run folder's scenario.scenic.
MAX_RUN_SCRIPT_BYTES = 4 * 1024 * 1024
#: A map file (.xodr); CARLA's largest town is about 30 MB.
MAX_MAP_BYTES = 256 * 1024 * 1024
#: The map cache is trimmed to this size (least recently used map folders go first).
MAP_CACHE_BUDGET_BYTES = 2 * 1024 * 1024 * 1024
#: A map folder used this recently is never evicted: a run may still be using it.
MAP_CACHE_IN_USE_SECONDS = 3600.0
#: A map's name: a safe file stem (no separators, no leading dot, so no `..`).
MAP_NAME_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,63}$"

# --- a re-check of a run folder's script ---------------------------------------------------
#: The longest wall-clock limit a run folder's report.json may ask for, seconds.
MAX_RECHECK_TIMEOUT = 600.0
MAX_SPAWN_ATTEMPTS = 1000
