"""Anthropic's Messages API (optional extra ``arise[anthropic]``).

Anthropic has no JSON mode; a forced tool call whose input schema is our schema gives the
same guarantee, so the structured style of this provider is ``tool``.
"""

from __future__ import annotations

import json
import time
from typing import Any

from arise.llm.base import BaseProvider
from arise.llm.retry import kind_for_status
from arise.llm.types import (
    Capabilities,
    Completion,
    ProviderError,
    ProviderErrorKind,
    ProviderUnavailable,
    Request,
    Usage,
)


class AnthropicProvider(BaseProvider):
    def __init__(
        self,
        *,
        name: str,
        model: str,
        api_key: str,
        capabilities: Capabilities,
        base_url: str | None = None,
        timeout: float = 300.0,
        key_env: str = "ANTHROPIC_API_KEY",
    ) -> None:
        try:
            import anthropic
        except ImportError as exc:
            raise ProviderUnavailable(
                "anthropic: the client is not installed; pip install 'arise[anthropic]'"
            ) from exc
        self.name = name
        self.model = model
        self.capabilities = capabilities
        self.key_env = key_env
        self._client = anthropic.Anthropic(
            api_key=api_key, base_url=base_url, timeout=timeout, max_retries=0
        )

    def _arguments(self, request: Request) -> dict[str, Any]:
        system_text = "\n\n".join(m.content for m in request.messages if m.role == "system")
        args: dict[str, Any] = {
            "model": self.model,
            "max_tokens": request.max_tokens,
            "temperature": request.temperature,
            "messages": [m.as_dict() for m in request.messages if m.role != "system"],
        }
        if system_text:
            args["system"] = system_text
        if request.stop:
            args["stop_sequences"] = list(request.stop)
        if request.json_schema is not None:
            tool = request.schema_name or "reply"
            args["tools"] = [
                {
                    "name": tool,
                    "description": "Give the answer as this tool's input.",
                    "input_schema": request.json_schema,
                }
            ]
            args["tool_choice"] = {"type": "tool", "name": tool}
        return args

    def send(self, request: Request) -> Completion:
        import anthropic

        started = time.perf_counter()
        try:
            reply = self._client.messages.create(**self._arguments(request))
        except anthropic.APITimeoutError as exc:
            raise ProviderError(
                f"{self.name}: no answer within the timeout", kind=ProviderErrorKind.TIMEOUT
            ) from exc
        except anthropic.APIConnectionError as exc:
            raise ProviderError(
                f"{self.name}: cannot reach the Anthropic API; check the network or ARISE_BASE_URL",
                kind=ProviderErrorKind.CONNECTION,
            ) from exc
        except anthropic.APIStatusError as exc:
            kind = kind_for_status(exc.status_code)
            hint = f"; check {self.key_env}" if kind is ProviderErrorKind.AUTH else ""
            retry_after = exc.response.headers.get("retry-after") if exc.response else None
            raise ProviderError(
                f"{self.name}: HTTP {exc.status_code}: {' '.join(str(exc.message).split())[:200]}{hint}",
                kind=kind,
                status=exc.status_code,
                retry_after=float(retry_after) if retry_after and retry_after.isdigit() else None,
            ) from exc
        latency = time.perf_counter() - started
        text = ""
        for block in reply.content:
            if block.type == "tool_use":
                text = json.dumps(block.input)
                break
            if block.type == "text":
                text += block.text
        return Completion(
            text=text,
            usage=Usage(
                calls=1,
                prompt_tokens=reply.usage.input_tokens,
                completion_tokens=reply.usage.output_tokens,
                seconds=latency,
            ),
            model=reply.model,
            latency=latency,
            provider=self.name,
            finish_reason=reply.stop_reason,
        )

    def close(self) -> None:
        self._client.close()
