"""Settings: presets < config file < environment < arguments; keys only from the environment."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from arise.llm import MissingCredentials, get_provider
from arise.llm.settings import PRESETS, ProviderKind, load_settings, with_overrides
from arise.llm.types import LLMError


def write_config(tmp_path: Path, text: str, monkeypatch: pytest.MonkeyPatch) -> Path:
    path = tmp_path / "config.toml"
    path.write_text(text)
    monkeypatch.setenv("ARISE_CONFIG", str(path))
    return path


def test_presets_cover_the_issue_list() -> None:
    for name in (
        "local",
        "openai",
        "deepseek",
        "gemini",
        "vllm",
        "ollama",
        "llamacpp",
        "anthropic",
        "replay",
    ):
        assert name in PRESETS
    # structured-output style is a per-backend fact, not a caller's guess
    assert PRESETS["openai"].structured == "json_schema"
    assert PRESETS["llamacpp"].structured == "json_object_schema"
    assert PRESETS["local"].structured == "json_object_schema"
    assert PRESETS["anthropic"].structured == "tool"
    assert PRESETS["deepseek"].structured == "json_object"


def test_default_is_the_embedded_model() -> None:
    settings = load_settings()
    assert settings.config_path is None
    assert settings.provider == "local"
    assert settings.profile().kind is ProviderKind.LOCAL


def test_file_then_env_then_arguments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    write_config(
        tmp_path,
        """
[llm]
provider = "gpu"
max_reasks = 3

[providers.gpu]
kind = "openai"
base_url = "http://127.0.0.1:9/v1"
model = "from-file"
api_key_env = "GPU_BOX_KEY"
structured = "json_schema"

[providers.local]
threads = 1
""",
        monkeypatch,
    )
    settings = load_settings()
    assert settings.provider == "gpu" and settings.max_reasks == 3
    assert settings.profile().model == "from-file"
    assert settings.profile().kind is ProviderKind.OPENAI  # parsed once, here
    assert settings.profile("local").threads == 1

    monkeypatch.setenv("ARISE_MODEL", "from-env")
    settings = load_settings()
    assert settings.profile().model == "from-env"
    assert with_overrides(settings, "gpu", model="from-arg").model == "from-arg"
    assert with_overrides(settings, "gpu", model=None).model == "from-env"

    monkeypatch.setenv("ARISE_PROVIDER", "local")
    monkeypatch.setenv("ARISE_LLM_THREADS", "2")
    settings = load_settings()
    assert settings.provider == "local" and settings.profile().threads == 2


@pytest.mark.parametrize("field", ["api_key", "token", "key"])
def test_a_key_in_a_config_file_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, field: str
) -> None:
    write_config(tmp_path, f'[providers.openai]\n{field} = "sk-abc"\n', monkeypatch)
    with pytest.raises(LLMError, match="environment"):
        load_settings()


def test_typo_in_config_is_reported(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    write_config(tmp_path, "[providers.local]\nthreds = 1\n", monkeypatch)
    with pytest.raises(LLMError, match="unknown setting 'threds'"):
        load_settings()
    write_config(tmp_path, '[providers.local]\nthreads = "many"\n', monkeypatch)
    with pytest.raises(LLMError, match="threads"):
        load_settings()


@pytest.mark.parametrize(
    ("provider", "env_var"),
    [
        ("openai", "OPENAI_API_KEY"),
        ("deepseek", "DEEPSEEK_API_KEY"),
        ("gemini", "GEMINI_API_KEY"),
        ("anthropic", "ANTHROPIC_API_KEY"),
    ],
)
def test_missing_key_names_the_variable(provider: str, env_var: str) -> None:
    with pytest.raises(MissingCredentials) as info:
        get_provider(provider)
    message = str(info.value)
    assert env_var in message and "\n" not in message
    assert info.value.env_var == env_var


def test_local_servers_need_no_key() -> None:
    llm = get_provider("llamacpp", cache=False)
    assert llm.capabilities.local and llm.name == "llamacpp"
    llm.close()


def test_unknown_provider_lists_the_known_ones() -> None:
    with pytest.raises(LLMError, match="known: .*openai"):
        get_provider("nope")


def _run_cli(
    *args: str, tmp_path: Path, extra: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    env = {
        k: v
        for k, v in os.environ.items()
        if not k.endswith(("_API_KEY", "_TOKEN")) and not k.startswith("ARISE_")
    }
    env["ARISE_CONFIG"] = str(tmp_path / "none.toml")
    env["ARISE_CACHE_DIR"] = str(tmp_path / "cache")
    env.update(extra or {})
    return subprocess.run(
        [sys.executable, "-m", "arise", "llm", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )


@pytest.mark.slow  # a new `arise` process (about 2 s)
def test_cli_missing_key_is_one_line(tmp_path: Path) -> None:
    result = _run_cli("ping", "--provider", "openai", tmp_path=tmp_path)
    assert result.returncode == 1
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "OPENAI_API_KEY" in lines[0] and "Traceback" not in result.stderr


@pytest.mark.slow  # a new `arise` process (about 2 s)
def test_cli_unreachable_server_is_one_line(tmp_path: Path) -> None:
    import socket

    with socket.socket() as sock:  # a port that nothing listens on
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    result = _run_cli(
        "ping",
        "--provider",
        "llamacpp",
        "--base-url",
        f"http://127.0.0.1:{port}/v1",
        tmp_path=tmp_path,
    )
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "cannot reach" in lines[0] and "ARISE_BASE_URL" in lines[0]


@pytest.mark.slow  # a new `arise` process (about 2 s)
def test_cli_info_shows_key_state_not_values(tmp_path: Path) -> None:
    env_key = "sk-test-1234567890abcdefghij"
    os.environ["OPENAI_API_KEY"] = env_key
    try:
        result = subprocess.run(
            [sys.executable, "-m", "arise", "llm", "info"],
            capture_output=True,
            text=True,
            env={**os.environ, "COLUMNS": "200"},
            timeout=120,
        )
    finally:
        del os.environ["OPENAI_API_KEY"]
    assert result.returncode == 0, result.stderr
    assert "key OPENAI_API_KEY: set" in result.stdout
    assert env_key not in result.stdout


def test_structured_style_and_kind_are_checked(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write_config(
        tmp_path, '[providers.gpu]\nkind = "openai"\nstructured = "jsonschema"\n', monkeypatch
    )
    with pytest.raises(LLMError, match="structured must be one of json_schema"):
        load_settings()
    write_config(tmp_path, '[providers.local]\nkind = "cloud"\n', monkeypatch)
    with pytest.raises(LLMError, match="kind must be one of"):
        load_settings()
    write_config(tmp_path, '[providers.box]\nkind = "Local"\n', monkeypatch)  # a new profile
    with pytest.raises(LLMError, match=r"\[providers.box\]: kind must be one of .*not 'Local'"):
        load_settings()
    write_config(tmp_path, '[providers.box]\nkind = "local"\n', monkeypatch)
    assert load_settings().profile("box").kind is ProviderKind.LOCAL


def test_threads_auto(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ARISE_LLM_THREADS", "auto")
    assert load_settings().profile("local").threads == 0


@pytest.mark.slow  # a new `arise` process (about 2 s)
def test_cli_missing_local_model_says_how_to_get_it(tmp_path: Path) -> None:
    result = _run_cli("ping", tmp_path=tmp_path, extra={"ARISE_MODELS_DIR": str(tmp_path)})
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "pip install 'arise[model]' && arise llm install-model" in lines[0]
    assert "ARISE_MODEL_PATH" in lines[0]
