"""OS-level confinement of a validation worker: Landlock, seccomp and resource limits.

A Scenic script is Python, so whatever a static check lets through, the process that runs
it must be unable to do harm. `confine()` is called once by a worker, after it has
imported Scenic and before it reads any script, and cannot be undone:

- Landlock (kernel ABI >= 1) limits the files it can open: read-only the interpreter, the
  installed packages and the map cache; read-write a private scratch folder; nothing else.
  ABI >= 4 adds TCP rules (no connect or bind except the CARLA ports), ABI >= 6 scopes
  signals and abstract UNIX sockets to the worker itself.
- seccomp (libseccomp through `pyseccomp`) refuses exec, new processes (threads still
  work), sockets, ptrace, mounts, namespaces, raising limits, changing file modes and
  owners (which Landlock does not cover), and kernel-facing calls a script never needs.
- rlimits bound memory, file size, open files, processes and core dumps.
- `enter_namespaces()` (called first, while the worker is one thread) gives it its own
  user, mount and (offline) network namespaces with a size-limited tmpfs as scratch.
- `isolate_child()` is what the fork server's child calls before it runs a script: no new
  processes at all, and a nested Landlock domain that cannot signal the server.

What could not be applied is reported, never hidden: the `SandboxReport` names what is
active and what is missing, and every check result carries it.
"""

from __future__ import annotations

import ctypes
import errno
import os
import resource
import sys
import threading
from dataclasses import dataclass
from pathlib import Path

from arise.validate.types import Mechanism, SandboxReport

# --- Landlock: the kernel's documented UAPI (include/uapi/linux/landlock.h) ---------------
_CREATE_RULESET_VERSION = 1
_RULE_PATH_BENEATH = 1
_RULE_NET_PORT = 2

_FS_EXECUTE = 1 << 0
_FS_WRITE_FILE = 1 << 1
_FS_READ_FILE = 1 << 2
_FS_READ_DIR = 1 << 3
_FS_REMOVE_DIR = 1 << 4
_FS_REMOVE_FILE = 1 << 5
_FS_MAKE_CHAR = 1 << 6
_FS_MAKE_DIR = 1 << 7
_FS_MAKE_REG = 1 << 8
_FS_MAKE_SOCK = 1 << 9
_FS_MAKE_FIFO = 1 << 10
_FS_MAKE_BLOCK = 1 << 11
_FS_MAKE_SYM = 1 << 12
_FS_REFER = 1 << 13  # ABI 2
_FS_TRUNCATE = 1 << 14  # ABI 3
_FS_IOCTL_DEV = 1 << 15  # ABI 5
_FILE_RIGHTS = _FS_EXECUTE | _FS_WRITE_FILE | _FS_READ_FILE | _FS_TRUNCATE | _FS_IOCTL_DEV

_NET_BIND_TCP = 1 << 0  # ABI 4
_NET_CONNECT_TCP = 1 << 1
_SCOPE_ABSTRACT_UNIX_SOCKET = 1 << 0  # ABI 6
_SCOPE_SIGNAL = 1 << 1

_PR_SET_NO_NEW_PRIVS = 38
_PR_SET_PDEATHSIG = 1

# unshare(2) and mount(2) flags (include/uapi/linux/sched.h, mount.h)
_CLONE_NEWNS = 0x00020000
_CLONE_NEWUSER = 0x10000000
_CLONE_NEWNET = 0x40000000
_MS_NOSUID, _MS_NODEV, _MS_NOEXEC = 0x2, 0x4, 0x8
_MS_REC, _MS_PRIVATE = 0x4000, 0x40000
NAMESPACE_PROCESS_LIMIT = 256  # tasks (threads count) a worker may have in its namespace

READ_ONLY = _FS_READ_FILE | _FS_READ_DIR
SCRATCH = (
    READ_ONLY
    | _FS_WRITE_FILE
    | _FS_TRUNCATE
    | _FS_REMOVE_FILE
    | _FS_REMOVE_DIR
    | _FS_MAKE_REG
    | _FS_MAKE_DIR
    | _FS_REFER
)
DEVICE = _FS_READ_FILE | _FS_WRITE_FILE


class _RulesetAttr(ctypes.Structure):
    _fields_ = [
        ("handled_access_fs", ctypes.c_uint64),
        ("handled_access_net", ctypes.c_uint64),
        ("scoped", ctypes.c_uint64),
    ]


class _PathBeneathAttr(ctypes.Structure):
    _pack_ = 1  # the kernel declares it packed
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


class _NetPortAttr(ctypes.Structure):
    _fields_ = [("allowed_access", ctypes.c_uint64), ("port", ctypes.c_uint64)]


# --- seccomp: what a script never needs ---------------------------------------------------
_DENIED_SYSCALLS = (
    # programs (new processes: see _NEW_PROCESSES)
    "execve",
    "execveat",
    # other processes' memory and descriptors
    "ptrace",
    "process_vm_readv",
    "process_vm_writev",
    "pidfd_getfd",
    "kcmp",
    # networking (offline: no sockets at all; CARLA mode re-allows TCP below)
    "socketpair",
    # mounts, namespaces, roots
    "mount",
    "umount2",
    "pivot_root",
    "chroot",
    "unshare",
    "setns",
    "move_mount",
    "open_tree",
    "fsopen",
    "fsmount",
    "fsconfig",
    "fspick",
    "mount_setattr",
    # limits may only shrink
    "setrlimit",
    # metadata Landlock does not cover: modes, owners, extended attributes
    "chmod",
    "fchmod",
    "fchmodat",
    "fchmodat2",
    "chown",
    "fchown",
    "lchown",
    "fchownat",
    "setxattr",
    "lsetxattr",
    "fsetxattr",
    "removexattr",
    "lremovexattr",
    "fremovexattr",
    "mknod",
    "mknodat",
    "open_by_handle_at",
    "name_to_handle_at",
    # the kernel itself
    "bpf",
    "perf_event_open",
    "keyctl",
    "add_key",
    "request_key",
    "init_module",
    "finit_module",
    "delete_module",
    "kexec_load",
    "kexec_file_load",
    "reboot",
    "swapon",
    "swapoff",
    "syslog",
    "acct",
    "quotactl",
    "iopl",
    "ioperm",
    "userfaultfd",
    "io_uring_setup",
    "io_uring_enter",
    "io_uring_register",
    "fanotify_init",
    "settimeofday",
    "clock_settime",
    "adjtimex",
    "sethostname",
    "setdomainname",
    "personality",
    "lookup_dcookie",
    "vhangup",
    # memory outside the address-space limit
    "memfd_create",
    "memfd_secret",
)
_NEW_PROCESSES = ("fork", "vfork")  # and clone without CLONE_THREAD
_CLONE_THREAD = 0x00010000
_AF_INET, _AF_INET6 = 2, 10
_SOCK_TYPE_MASK = 0xF  # the type bits of socket()'s second argument (flags above)


@dataclass(frozen=True)
class ConfinementPolicy:
    """What one worker may touch once confined."""

    read_only: tuple[Path, ...]
    scratch: Path
    devices: tuple[Path, ...] = (
        Path("/dev/null"),
        Path("/dev/zero"),
        Path("/dev/urandom"),
        Path("/dev/random"),
    )
    # TCP ports the worker may connect to (the CARLA server's); empty: no network at all.
    connect_ports: tuple[int, ...] = ()
    # A fork server (the validation worker) may fork the children that run scripts; each
    # child then calls `isolate_child()` before it touches a script.
    allow_fork: bool = False
    memory_bytes: int | None = None
    file_size_bytes: int = 64 * 1024 * 1024
    open_files: int = 256
    extra_processes: int = 64  # threads count as processes for RLIMIT_NPROC
    # Set when the process already runs in its own namespaces (enter_namespaces).
    in_namespaces: bool = False


def python_policy(
    scratch: Path,
    *,
    memory_mb: int = 0,
    connect_ports: tuple[int, ...] = (),
    read_also: tuple[Path, ...] = (),
) -> ConfinementPolicy:
    """The policy for a Python process of ours: read the interpreter, the installed
    packages, arise itself and the map cache; write only `scratch`."""
    import arise
    from arise.paths import cache_dir

    readable = {Path(p) for p in (sys.prefix, sys.base_prefix, sys.exec_prefix)}
    readable |= {Path(p) for p in sys.path if p and Path(p).is_dir()}
    readable |= {
        Path(arise.__file__).parents[1],
        cache_dir() / "maps",
        cache_dir() / "matplotlib",
        Path("/usr"),
        Path("/lib"),
        Path("/lib64"),
        Path("/etc/ld.so.cache"),
        Path("/etc/localtime"),
        *read_also,
    }
    if connect_ports:  # name resolution for the CARLA host
        readable |= {Path("/etc/hosts"), Path("/etc/nsswitch.conf"), Path("/etc/gai.conf")}
    readable = {p.resolve() for p in readable if p.exists()} - {scratch.resolve()}
    memory = None
    if memory_mb > 0:
        import psutil

        memory = psutil.Process().memory_info().vms + memory_mb * 1024 * 1024
    return ConfinementPolicy(
        read_only=tuple(sorted(readable)),
        scratch=scratch,
        connect_ports=connect_ports,
        memory_bytes=memory,
    )


def enter_namespaces(scratch: Path, scratch_bytes: int, network: bool) -> str | None:
    """Move this (still single-threaded) process into its own user and mount namespaces,
    and into an empty network namespace unless it needs the network; mount a tmpfs of
    `scratch_bytes` on `scratch`. Returns why not, or None when done.

    In its own user namespace the process limit binds even when the user is root (the
    kernel exempts only root of the initial namespace), the scratch folder cannot grow
    past its size, and offline there is no interface but a loopback that is down.
    """
    if not sys.platform.startswith("linux"):
        return "namespaces exist only on Linux"
    if threading.active_count() > 1:
        return "namespaces need a single-threaded process"
    libc = _libc()
    uid, gid = os.getuid(), os.getgid()
    flags = _CLONE_NEWUSER | _CLONE_NEWNS | (0 if network else _CLONE_NEWNET)
    if libc.unshare(flags) != 0:
        return f"unshare: {os.strerror(ctypes.get_errno())} (user namespaces disabled?)"
    try:
        for name, text in (
            ("setgroups", "deny"),
            ("uid_map", f"{uid} {uid} 1"),
            ("gid_map", f"{gid} {gid} 1"),
        ):
            with open(f"/proc/self/{name}", "w") as handle:
                handle.write(text)
    except OSError as error:
        return f"user namespace maps: {error}"
    if libc.mount(b"none", b"/", None, _MS_REC | _MS_PRIVATE, None) != 0:
        return f"private mounts: {os.strerror(ctypes.get_errno())}"
    options = f"size={scratch_bytes},mode=0700".encode()
    if (
        libc.mount(
            b"tmpfs", str(scratch).encode(), b"tmpfs", _MS_NOSUID | _MS_NODEV | _MS_NOEXEC, options
        )
        != 0
    ):
        return f"tmpfs scratch: {os.strerror(ctypes.get_errno())}"
    return None


def _libc() -> ctypes.CDLL:
    return ctypes.CDLL(None, use_errno=True)


def _syscall_number(name: str) -> int | None:
    """The native syscall number, resolved by libseccomp (no hand-written numbers)."""
    try:
        import pyseccomp
    except (ImportError, OSError):
        return None
    number = int(pyseccomp.resolve_syscall(pyseccomp.Arch.NATIVE, name))
    return number if number >= 0 else None


def landlock_abi() -> int:
    """The Landlock ABI version this kernel offers, 0 when it offers none."""
    number = _syscall_number("landlock_create_ruleset")
    if number is None or not sys.platform.startswith("linux"):
        return 0
    libc = _libc()
    libc.syscall.restype = ctypes.c_long
    version = libc.syscall(
        ctypes.c_long(number), None, ctypes.c_size_t(0), ctypes.c_uint32(_CREATE_RULESET_VERSION)
    )
    return max(0, int(version))


def seccomp_available() -> bool:
    try:
        import pyseccomp

        pyseccomp.SyscallFilter(pyseccomp.ALLOW)
    except (ImportError, OSError, AttributeError):
        return False
    return sys.platform.startswith("linux")


def _no_new_privs(libc: ctypes.CDLL) -> None:
    if libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0:
        raise OSError(ctypes.get_errno(), "prctl(PR_SET_NO_NEW_PRIVS) failed")


def _fs_rights(abi: int) -> int:
    rights = (1 << 13) - 1  # EXECUTE .. MAKE_SYM, ABI 1
    if abi >= 2:
        rights |= _FS_REFER
    if abi >= 3:
        rights |= _FS_TRUNCATE
    if abi >= 5:
        rights |= _FS_IOCTL_DEV
    return rights


def _apply_landlock(policy: ConfinementPolicy, abi: int) -> list[Mechanism]:
    """Restrict this thread (and all it starts) to the policy; returns what is active."""
    names: dict[str, int] = {}
    for name in ("landlock_create_ruleset", "landlock_add_rule", "landlock_restrict_self"):
        number = _syscall_number(name)
        if number is None:
            raise OSError(errno.ENOSYS, f"libseccomp does not know the syscall {name}")
        names[name] = number
    libc = _libc()
    libc.syscall.restype = ctypes.c_long
    handled_fs = _fs_rights(abi)
    attr = _RulesetAttr(
        handled_access_fs=handled_fs,
        handled_access_net=(_NET_BIND_TCP | _NET_CONNECT_TCP) if abi >= 4 else 0,
        scoped=(_SCOPE_ABSTRACT_UNIX_SOCKET | _SCOPE_SIGNAL) if abi >= 6 else 0,
    )
    size = 24 if abi >= 6 else 16 if abi >= 4 else 8
    ruleset = libc.syscall(
        ctypes.c_long(names["landlock_create_ruleset"]),
        ctypes.byref(attr),
        ctypes.c_size_t(size),
        ctypes.c_uint32(0),
    )
    if ruleset < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset failed")
    try:
        grants = [(path, READ_ONLY) for path in policy.read_only]
        grants += [(policy.scratch, SCRATCH)] + [(path, DEVICE) for path in policy.devices]
        for path, rights in grants:
            try:
                fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
            except OSError:
                continue  # a path this machine lacks grants nothing
            try:
                allowed = rights & handled_fs
                if not os.path.isdir(path):
                    allowed &= _FILE_RIGHTS
                rule = _PathBeneathAttr(allowed_access=allowed, parent_fd=fd)
                if (
                    libc.syscall(
                        ctypes.c_long(names["landlock_add_rule"]),
                        ctypes.c_int(ruleset),
                        ctypes.c_int(_RULE_PATH_BENEATH),
                        ctypes.byref(rule),
                        ctypes.c_uint32(0),
                    )
                    != 0
                ):
                    raise OSError(ctypes.get_errno(), f"landlock_add_rule failed for {path}")
            finally:
                os.close(fd)
        if abi >= 4:
            for port in policy.connect_ports:
                net_rule = _NetPortAttr(allowed_access=_NET_CONNECT_TCP, port=port)
                if (
                    libc.syscall(
                        ctypes.c_long(names["landlock_add_rule"]),
                        ctypes.c_int(ruleset),
                        ctypes.c_int(_RULE_NET_PORT),
                        ctypes.byref(net_rule),
                        ctypes.c_uint32(0),
                    )
                    != 0
                ):
                    raise OSError(ctypes.get_errno(), f"landlock_add_rule failed for port {port}")
        _no_new_privs(libc)
        if (
            libc.syscall(
                ctypes.c_long(names["landlock_restrict_self"]),
                ctypes.c_int(ruleset),
                ctypes.c_uint32(0),
            )
            != 0
        ):
            raise OSError(ctypes.get_errno(), "landlock_restrict_self failed")
    finally:
        os.close(ruleset)
    active = [Mechanism.LANDLOCK_FS]
    if abi >= 4:
        active.append(Mechanism.LANDLOCK_NET)
    if abi >= 6:
        active.append(Mechanism.LANDLOCK_SCOPE)
    return active


def _apply_seccomp(policy: ConfinementPolicy) -> None:
    import pyseccomp as sc

    refuse = sc.ERRNO(errno.EPERM)
    rules = sc.SyscallFilter(sc.ALLOW)
    rules.set_attr(sc.Attr.CTL_TSYNC, 1)  # every thread of the process, not just this one
    for name in _DENIED_SYSCALLS:
        if _syscall_number(name) is not None:
            rules.add_rule(refuse, name)
    if not policy.allow_fork:
        _refuse_new_processes(rules)
    # clone3 hides its flags in memory, so it answers ENOSYS and the C library falls back
    # to clone, whose flags a filter can read.
    if _syscall_number("clone3") is not None:
        rules.add_rule(sc.ERRNO(errno.ENOSYS), "clone3")
    # prlimit64 may read limits, never set them.
    rules.add_rule(refuse, "prlimit64", sc.Arg(2, sc.NE, 0))
    if policy.connect_ports:
        # CARLA: TCP over IPv4/IPv6 only; Landlock holds the ports.
        for family in (*range(0, _AF_INET), *range(_AF_INET + 1, _AF_INET6)):
            rules.add_rule(sc.ERRNO(errno.EACCES), "socket", sc.Arg(0, sc.EQ, family))
        rules.add_rule(sc.ERRNO(errno.EACCES), "socket", sc.Arg(0, sc.GT, _AF_INET6))
        for kind in range(2, 11):
            rules.add_rule(
                sc.ERRNO(errno.EACCES), "socket", sc.Arg(1, sc.MASKED_EQ, _SOCK_TYPE_MASK, kind)
            )
    else:
        rules.add_rule(sc.ERRNO(errno.EACCES), "socket")
    rules.load()


def _refuse_new_processes(rules: object) -> None:
    import pyseccomp as sc

    assert isinstance(rules, sc.SyscallFilter)
    refuse = sc.ERRNO(errno.EPERM)
    for name in _NEW_PROCESSES:
        rules.add_rule(refuse, name)
    rules.add_rule(refuse, "clone", sc.Arg(0, sc.MASKED_EQ, _CLONE_THREAD, 0))


def isolate_child() -> None:
    """For the child a fork server starts for each script: stack a seccomp filter that
    refuses new processes (threads still work) and leaving the server's process group or
    dropping the parent-death signal (so it dies with its server), and enter a nested
    Landlock domain whose scopes keep its signals and abstract sockets from reaching the
    server. Both only add restrictions: neither can be undone."""
    import pyseccomp as sc

    rules = sc.SyscallFilter(sc.ALLOW)
    rules.set_attr(sc.Attr.CTL_TSYNC, 1)
    _refuse_new_processes(rules)
    refuse = sc.ERRNO(errno.EPERM)
    for name in ("setsid", "setpgid"):
        rules.add_rule(refuse, name)
    rules.add_rule(refuse, "prctl", sc.Arg(0, sc.EQ, _PR_SET_PDEATHSIG))
    rules.load()
    abi = landlock_abi()
    if abi >= 6:
        _apply_landlock_scopes()


def _apply_landlock_scopes() -> None:
    libc = _libc()
    libc.syscall.restype = ctypes.c_long
    create = _syscall_number("landlock_create_ruleset")
    restrict = _syscall_number("landlock_restrict_self")
    if create is None or restrict is None:
        raise OSError(errno.ENOSYS, "libseccomp does not know the Landlock syscalls")
    attr = _RulesetAttr(
        handled_access_fs=0,
        handled_access_net=0,
        scoped=_SCOPE_ABSTRACT_UNIX_SOCKET | _SCOPE_SIGNAL,
    )
    ruleset = libc.syscall(
        ctypes.c_long(create), ctypes.byref(attr), ctypes.c_size_t(24), ctypes.c_uint32(0)
    )
    if ruleset < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset (scopes) failed")
    try:
        if libc.syscall(ctypes.c_long(restrict), ctypes.c_int(ruleset), ctypes.c_uint32(0)) != 0:
            raise OSError(ctypes.get_errno(), "landlock_restrict_self (scopes) failed")
    finally:
        os.close(ruleset)


def _apply_rlimits(policy: ConfinementPolicy) -> None:
    def cap(kind: int, value: int) -> None:
        soft, hard = resource.getrlimit(kind)
        if hard != resource.RLIM_INFINITY:
            value = min(value, hard)
        resource.setrlimit(kind, (value, value))

    if policy.memory_bytes:
        cap(resource.RLIMIT_AS, policy.memory_bytes)
    cap(resource.RLIMIT_FSIZE, policy.file_size_bytes)
    cap(resource.RLIMIT_NOFILE, policy.open_files)
    cap(resource.RLIMIT_CORE, 0)
    if policy.in_namespaces:  # counted per namespace: only this worker's own tasks
        cap(resource.RLIMIT_NPROC, NAMESPACE_PROCESS_LIMIT)
    else:
        cap(resource.RLIMIT_NPROC, _processes_of_user() + policy.extra_processes)


def _processes_of_user() -> int:
    """Tasks (processes and threads) the real user runs now; RLIMIT_NPROC counts them all."""
    try:
        import psutil

        uid = os.getuid()
        return sum(
            p.info["num_threads"] or 1
            for p in psutil.process_iter(["uids", "num_threads"])
            if p.info["uids"] is not None and p.info["uids"].real == uid
        )
    except Exception:  # noqa: BLE001  (a best guess is enough for a limit)
        return 4096


def confine(policy: ConfinementPolicy) -> SandboxReport:
    """Confine this process for good; report what is active and what could not be."""
    report = SandboxReport()
    if threading.active_count() > 1:
        report.notes.append(
            f"{threading.active_count()} threads were running at confinement; "
            "Landlock covers only the calling thread's descendants"
        )
    try:
        _apply_rlimits(policy)
        report.active.append(Mechanism.RLIMITS)
    except (OSError, ValueError) as error:
        report.notes.append(f"rlimits: {error}")
    abi = landlock_abi()
    report.landlock_abi = abi
    if abi == 0:
        report.notes.append(
            "Landlock: this kernel offers none (Linux >= 5.13 with "
            "CONFIG_SECURITY_LANDLOCK and lsm=landlock)"
        )
    else:
        try:
            report.active.extend(_apply_landlock(policy, abi))
        except OSError as error:
            report.notes.append(f"Landlock: {error}")
        if abi < 4:
            report.notes.append(f"Landlock ABI {abi} has no network rules (needs 4)")
        elif abi < 6:
            report.notes.append(f"Landlock ABI {abi} cannot scope signals (needs 6)")
    if seccomp_available():
        try:
            _apply_seccomp(policy)
            report.active.append(Mechanism.SECCOMP)
        except (OSError, ValueError, RuntimeError) as error:
            report.notes.append(f"seccomp: {error}")
    else:
        report.notes.append("seccomp: libseccomp (libseccomp.so.2) or pyseccomp is missing")
    if policy.in_namespaces:
        report.active.append(Mechanism.NAMESPACES)
    report.missing = [m for m in Mechanism if m not in report.active]
    return report


def required_by_settings() -> bool:
    """Whether the user asked, once for all runs, never to run a script without full
    confinement: `ARISE_REQUIRE_SANDBOX=1` or `[sandbox] require = true` in the config."""
    flag = os.environ.get("ARISE_REQUIRE_SANDBOX", "").strip().lower()
    if flag:
        return flag in ("1", "true", "yes", "on")
    import tomllib

    from arise.paths import config_path

    try:
        table = tomllib.loads(config_path().read_text(encoding="utf-8")).get("sandbox", {})
    except (OSError, tomllib.TOMLDecodeError):
        return False
    return isinstance(table, dict) and table.get("require") is True


def kernel_support() -> SandboxReport:
    """What this machine could apply, without applying anything (for `arise doctor`)."""
    report = SandboxReport()
    report.landlock_abi = abi = landlock_abi()
    report.active.append(Mechanism.RLIMITS)
    if abi >= 1:
        report.active.append(Mechanism.LANDLOCK_FS)
    if abi >= 4:
        report.active.append(Mechanism.LANDLOCK_NET)
    if abi >= 6:
        report.active.append(Mechanism.LANDLOCK_SCOPE)
    if seccomp_available():
        report.active.append(Mechanism.SECCOMP)
    if _user_namespaces_allowed():
        report.active.append(Mechanism.NAMESPACES)
    report.missing = [m for m in Mechanism if m not in report.active]
    return report


def _user_namespaces_allowed() -> bool:
    try:
        limit = Path("/proc/sys/user/max_user_namespaces").read_text().strip()
    except OSError:
        return False
    return limit.isdigit() and int(limit) > 0
