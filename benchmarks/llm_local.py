"""Embedded local model: prefix reuse and throughput, through arise's own LocalProvider.

    .venv/bin/python benchmarks/llm_local.py [--threads 1,2] [--json out/llm_local.json]

1. Prefix reuse: two calls that share a ~1000-token prefix (system prompt + examples)
   and differ in the last question. The second call's time to first token should be a
   fraction of the first: llama.cpp keeps the evaluated prefix in its KV cache.
2. Throughput for each thread count: prompt tokens/s on a fresh ~1000-token prompt and
   generation tokens/s on a 128-token answer, from llama.cpp's own counters.

The load average is printed before and after: on 2 cores another busy process changes
the numbers a lot (FACTS.md: 2 threads next to a busy core collapse), so read them
together. Nothing is cached across runs; each prompt starts with a nonce.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path
from typing import Any

from arise.llm import local
from arise.llm.local import LocalProvider
from arise.llm.types import Completion, Request, system, user

ACTORS = ["pedestrian", "cyclist", "motorcyclist", "truck", "bus", "parked car", "scooter"]
PLACES = ["a four-way junction", "a straight two-lane road", "a roundabout", "a highway ramp"]
ACTIONS = ["crosses from the left", "brakes suddenly", "cuts in", "runs a red light", "stops"]


def shared_prefix(nonce: str, examples: int) -> str:
    """A deterministic system prompt of the shape the pipeline sends (rules + few-shot)."""
    lines = [
        f"[{nonce}] You turn traffic scenario descriptions into structured specifications.",
        "Fields: adversary type, adversary behavior, road geometry, spawn position, weather.",
        "Answer in one short sentence per field. Use only the listed field names.",
        "Examples follow.",
    ]
    for i in range(examples):
        actor = ACTORS[i % len(ACTORS)]
        place = PLACES[i % len(PLACES)]
        action = ACTIONS[i % len(ACTIONS)]
        lines.append(
            f"Example {i + 1}: On {place}, a {actor} {action} while the ego vehicle approaches "
            f"at {20 + i} km/h. -> adversary type: {actor}; adversary behavior: {action}; "
            f"road geometry: {place}; spawn position: {10 + i} m ahead, right lane; "
            f"weather: {'rain' if i % 3 == 0 else 'clear'}."
        )
    return "\n".join(lines)


def prefix_of_about(provider: LocalProvider, nonce: str, target_tokens: int) -> str:
    """Grow the example list until the prefix tokenizes to about ``target_tokens``."""
    llama = local.loaded_model()
    assert llama is not None
    examples = 1
    while True:
        text = shared_prefix(nonce, examples)
        if len(llama.tokenize(text.encode(), add_bos=False)) >= target_tokens:
            return text
        examples += 1


def call(provider: LocalProvider, prefix: str, question: str, max_tokens: int) -> Completion:
    request = Request.build([system(prefix), user(question)], max_tokens=max_tokens)
    return provider.send(request)


def row(c: Completion) -> dict[str, Any]:
    d = c.details
    return {
        "prompt_tokens": c.usage.prompt_tokens,
        "prompt_tokens_evaluated": d["prompt_tokens_evaluated"],
        "ttft_s": round(c.first_token_latency or 0.0, 3),
        "latency_s": round(c.latency, 3),
        "completion_tokens": c.usage.completion_tokens,
    }


def load() -> list[float]:
    return [round(x, 2) for x in os.getloadavg()]


def cpu_snapshot() -> tuple[float, float, float]:
    """(all busy CPU seconds on the machine, this process's CPU seconds, wall time)."""
    with open("/proc/stat") as fh:
        fields = [int(x) for x in fh.readline().split()[1:]]
    tick = os.sysconf("SC_CLK_TCK")
    user, nice, system_, _idle, _iowait, irq, softirq, steal = fields[:8]
    busy = (user + nice + system_ + irq + softirq + steal) / tick
    own = os.times()
    return busy, own.user + own.system, time.monotonic()


def others_cores(before: tuple[float, float, float]) -> float:
    """Cores used on average by *other* processes since ``before`` (the load average
    counts our own threads too, so it cannot tell a quiet machine from a busy one)."""
    busy, own, wall = cpu_snapshot()
    return round(max(0.0, (busy - before[0]) - (own - before[1])) / max(wall - before[2], 1e-9), 2)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "--model-path", default=None, help="GGUF (default: the installed default model)"
    )
    parser.add_argument("--threads", default="1,2", help="thread counts to compare, e.g. 1,2")
    parser.add_argument("--reuse-threads", type=int, default=2, help="threads for the prefix test")
    parser.add_argument("--prefix-tokens", type=int, default=1000)
    parser.add_argument("--gen-tokens", type=int, default=128)
    parser.add_argument("--skip-reuse", action="store_true", help="only the throughput part")
    parser.add_argument("--json", type=Path, default=None, help="also write the results here")
    args = parser.parse_args()

    nonce = f"{time.time_ns():x}"
    result: dict[str, Any] = {
        "date": time.strftime("%Y-%m-%d %H:%M"),
        "machine": f"{os.cpu_count()} cores, {platform.machine()}, Python {platform.python_version()}",
        "load_before": load(),
    }
    provider = LocalProvider(model_path=args.model_path, threads=args.reuse_threads)
    result["model"] = provider.model
    try:
        import llama_cpp

        result["llama_cpp_python"] = llama_cpp.__version__
    except (ImportError, AttributeError):
        pass

    # Warm-up: load the weights and run one tiny call so the first measured call is not
    # also paying for first-use allocations.
    warm = provider.send(Request.build([user("Say ok.")], max_tokens=2))
    result["load_seconds"] = round(warm.details.get("load_seconds", 0.0), 2)

    # 1. prefix reuse
    if not args.skip_reuse:
        prefix = prefix_of_about(provider, f"reuse-{nonce}", args.prefix_tokens)
        snap = cpu_snapshot()
        first = call(
            provider, prefix, "A cyclist swerves into the lane at dusk. Give the fields.", 16
        )
        second = call(
            provider, prefix, "A bus stops at a bus stop in the rain. Give the fields.", 16
        )
        ratio = (first.first_token_latency or 0) / max(second.first_token_latency or 1e-9, 1e-9)
        result["prefix_reuse"] = {
            "threads": args.reuse_threads,
            "first": row(first),
            "second": row(second),
            "ttft_ratio": round(ratio, 1),
            "other_processes_cores": others_cores(snap),
        }

    # 2. throughput per thread count
    result["throughput"] = []
    for threads in [int(t) for t in args.threads.split(",") if t.strip()]:
        provider.set_threads(threads)
        fresh = prefix_of_about(provider, f"tp{threads}-{nonce}", args.prefix_tokens)
        snap = cpu_snapshot()
        prompt_call = call(provider, fresh, "Say ok.", 1)
        d = prompt_call.details
        gen_call = provider.send(
            Request.build(
                [user("Count from 1 to 300, one number per line, no other text.")],
                max_tokens=args.gen_tokens,
            )
        )
        g = gen_call.details
        result["throughput"].append(
            {
                "threads": threads,
                "prompt_tokens": d["prompt_tokens_evaluated"],
                "prompt_tok_s": round(d["prompt_tokens_evaluated"] / d["prompt_eval_seconds"], 1),
                "gen_tokens": g["generated_tokens_evaluated"],
                "gen_tok_s": round(g["generated_tokens_evaluated"] / g["generation_seconds"], 1),
                "load_after": load(),
                "other_processes_cores": others_cores(snap),
            }
        )
    result["load_after"] = load()

    print(f"# LLM local benchmark ({result['date']}, {result['machine']})")
    print(
        f"model {result['model']}, llama-cpp-python {result.get('llama_cpp_python', '?')}, "
        f"load {result['load_seconds']} s; load average before {result['load_before']}, "
        f"after {result['load_after']}"
    )
    print()
    reuse = result.get("prefix_reuse")
    if reuse:
        print(
            f"Prefix reuse ({reuse['threads']} threads, ~{args.prefix_tokens}-token shared prefix):"
        )
        print("| call | prompt tokens | evaluated | time to first token (s) | total (s) |")
        print("|---|---:|---:|---:|---:|")
        for name in ("first", "second"):
            r = reuse[name]
            print(
                f"| {name} | {r['prompt_tokens']} | {r['prompt_tokens_evaluated']} "
                f"| {r['ttft_s']} | {r['latency_s']} |"
            )
        print(
            f"\nTTFT first / second = {reuse['ttft_ratio']}x "
            f"(other processes used {reuse['other_processes_cores']} cores meanwhile)"
        )
        print()
    print("| threads | prompt tok/s | gen tok/s | other processes (cores) | load average after |")
    print("|---:|---:|---:|---:|---|")
    for t in result["throughput"]:
        print(
            f"| {t['threads']} | {t['prompt_tok_s']} ({t['prompt_tokens']} tok) | "
            f"{t['gen_tok_s']} ({t['gen_tokens']} tok) | {t['other_processes_cores']} | "
            f"{t['load_after']} |"
        )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
