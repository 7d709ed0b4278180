"""`arise search`: VerifAI's samplers look for the most critical instance of a script.

The script's free parameters (`OPT_*` ranges and VerifAI parameters) span the space;
VerifAI's random, Halton, cross-entropy or Bayesian-optimisation sampler proposes values;
each trial runs in the confined validator with the values fixed; the trace's
time-to-collision, closest approach or contact scores it; every trial is saved in SQLite.
"""

from arise.evaluate.search.errors import (
    NoFreeParameters,
    SamplerUnavailable,
    SearchError,
    StoreMismatch,
)
from arise.evaluate.search.executor import Executor
from arise.evaluate.search.objective import CRITICAL_TTC, Objective, TrialOutcome
from arise.evaluate.search.outputs import SearchFiles, write_outputs
from arise.evaluate.search.runner import SearchConfig, SearchResult, resolve_script, run_search
from arise.evaluate.search.sampler import SamplerKind, verifai_available
from arise.evaluate.search.space import FreeParam, ParamKind, find_free_params, fix_params
from arise.evaluate.search.store import SearchStore, TrialRecord

__all__ = [
    "CRITICAL_TTC",
    "Executor",
    "FreeParam",
    "NoFreeParameters",
    "Objective",
    "ParamKind",
    "SamplerKind",
    "SamplerUnavailable",
    "SearchConfig",
    "SearchError",
    "SearchFiles",
    "SearchResult",
    "SearchStore",
    "StoreMismatch",
    "TrialOutcome",
    "TrialRecord",
    "find_free_params",
    "fix_params",
    "resolve_script",
    "run_search",
    "verifai_available",
    "write_outputs",
]
