"""LLM providers behind one small protocol. Typical use:

from arise.llm import get_provider
llm = get_provider()                       # settings: config file + ARISE_* env
reply = llm.complete([{"role": "user", "content": "..."}], max_tokens=200, schema=Spec)
reply.parsed, reply.usage, llm.total      # validated object, this call, the whole run
"""

from arise.llm.base import BaseProvider, Provider
from arise.llm.registry import get_provider
from arise.llm.types import (
    Capabilities,
    Completion,
    LLMError,
    Message,
    MissingCredentials,
    ModelNotInstalled,
    ProviderError,
    ProviderErrorKind,
    ProviderUnavailable,
    ReplayMiss,
    Request,
    StructuredOutputFailed,
    Usage,
)

__all__ = [
    "BaseProvider",
    "Capabilities",
    "Completion",
    "LLMError",
    "Message",
    "MissingCredentials",
    "ModelNotInstalled",
    "Provider",
    "ProviderError",
    "ProviderErrorKind",
    "ProviderUnavailable",
    "ReplayMiss",
    "Request",
    "StructuredOutputFailed",
    "Usage",
    "get_provider",
]
