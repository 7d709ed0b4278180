"""Any server that speaks OpenAI's chat-completions API, through the official client.

OpenAI, DeepSeek, Gemini's OpenAI endpoint, vLLM, Ollama and llama.cpp servers differ only
in base URL, key and how they accept a JSON schema; those differences are settings and
capability flags, not subclasses.
"""

from __future__ import annotations

import time
from typing import Any

from arise.llm.base import BaseProvider
from arise.llm.retry import kind_for_status
from arise.llm.structured import response_format
from arise.llm.types import (
    Capabilities,
    Completion,
    ProviderError,
    ProviderErrorKind,
    Request,
    Usage,
)


def _retry_after(headers: Any) -> float | None:
    try:
        value = headers.get("retry-after") if headers is not None else None
        return float(value) if value is not None else None
    except (TypeError, ValueError):
        return None


class OpenAICompatProvider(BaseProvider):
    def __init__(
        self,
        *,
        name: str,
        model: str,
        base_url: str,
        api_key: str | None,
        capabilities: Capabilities,
        timeout: float = 300.0,
        key_env: str | None = None,
    ) -> None:
        import openai

        self.name = name
        self.model = model
        self.base_url = base_url
        self.capabilities = capabilities
        self.key_env = key_env
        # Local servers ignore the key, but the client insists on one.
        self._client = openai.OpenAI(
            base_url=base_url,
            api_key=api_key or "not-needed",
            timeout=timeout,
            max_retries=0,  # retries belong to retry.py's table, not to the client
        )

    def _arguments(self, request: Request) -> dict[str, Any]:
        args: dict[str, Any] = {
            "model": self.model,
            "messages": [m.as_dict() for m in request.messages],
            "temperature": request.temperature,
            "max_tokens": request.max_tokens,
        }
        if request.stop:
            args["stop"] = list(request.stop)
        if request.seed is not None and self.capabilities.seed:
            args["seed"] = request.seed
        fmt = response_format(
            self.capabilities.structured, request.json_schema, request.schema_name
        )
        if fmt is not None:
            args["response_format"] = fmt
        return args

    def send(self, request: Request) -> Completion:
        import openai

        started = time.perf_counter()
        try:
            reply = self._client.chat.completions.create(**self._arguments(request))
        except openai.APITimeoutError as exc:
            raise ProviderError(
                f"{self.name}: no answer from {self.base_url} within the timeout "
                f"(raise ARISE_LLM_TIMEOUT or use a smaller model)",
                kind=ProviderErrorKind.TIMEOUT,
            ) from exc
        except openai.APIConnectionError as exc:
            raise ProviderError(
                f"{self.name}: cannot reach {self.base_url}; start the server or set "
                f"ARISE_BASE_URL to where it listens",
                kind=ProviderErrorKind.CONNECTION,
            ) from exc
        except openai.APIStatusError as exc:
            raise self._status_error(exc) from exc
        latency = time.perf_counter() - started
        if not reply.choices:
            raise ProviderError(
                f"{self.name}: the server returned no choices", kind=ProviderErrorKind.OTHER
            )
        choice = reply.choices[0]
        usage = reply.usage
        return Completion(
            text=choice.message.content or "",
            usage=Usage(
                calls=1,
                prompt_tokens=usage.prompt_tokens if usage else 0,
                completion_tokens=usage.completion_tokens if usage else 0,
                seconds=latency,
            ),
            model=reply.model or self.model,
            latency=latency,
            provider=self.name,
            finish_reason=choice.finish_reason,
        )

    def _status_error(self, exc: Any) -> ProviderError:
        status = getattr(exc, "status_code", None)
        kind = kind_for_status(status)
        detail = " ".join(str(getattr(exc, "message", exc)).split())[:200]
        if kind is ProviderErrorKind.AUTH:
            hint = f"check {self.key_env}" if self.key_env else "check the API key"
            text = f"{self.name}: the server refused the key (HTTP {status}); {hint}"
        elif kind is ProviderErrorKind.NOT_FOUND:
            text = (
                f"{self.name}: HTTP 404 from {self.base_url} for model {self.model!r}; "
                f"check ARISE_BASE_URL and ARISE_MODEL ({detail})"
            )
        else:
            text = f"{self.name}: HTTP {status} from {self.base_url}: {detail}"
        response = getattr(exc, "response", None)
        return ProviderError(
            text,
            kind=kind,
            status=status,
            retry_after=_retry_after(getattr(response, "headers", None)),
        )

    def served_models(self, limit: int = 5) -> list[str]:
        """Model ids the server lists (a local server shows what it actually loaded).

        Best effort: servers without ``/models`` or any error give an empty list.
        """
        try:
            page = self._client.models.list()
            return [m.id for _, m in zip(range(limit + 1), page, strict=False)]
        except Exception:  # noqa: BLE001 - purely informational
            return []

    def close(self) -> None:
        self._client.close()
