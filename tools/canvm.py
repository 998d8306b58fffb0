#!/usr/bin/env python3
"""Run a command with a real SocketCAN interface (vcan0) up: directly where the host kernel has
AF_CAN, otherwise inside a small QEMU virtual machine that boots Debian's own kernel.

  tools/canvm.py check               which path is available here, and why
  tools/canvm.py prepare             download the kernel and build the initramfs (cached)
  tools/canvm.py run -- CMD ARGS...  run CMD ARGS... as one shell command line with vcan0 up

`run` joins the words after `--` with spaces and hands them to /bin/sh -c (as ssh does), in the
current directory and environment, with standard input from /dev/null. The command's stdout and
stderr are passed through and its exit status is canvm's. canvm's own statuses: 77 skipped (no
path to SocketCAN here; the reason on stderr), 124 timed out, 125 canvm or the VM failed.

Direct path: the host has AF_CAN; the command runs in a fresh network namespace (unshare) where
vcan0 is created, so runs in parallel do not share a bus. Without a namespace it uses the host's
vcan0 if that is up (see docs/socketcan.md).

VM path: qemu-system-x86_64 boots the kernel of the package that linux-image-amd64 depends on
(fetched with `apt-get download`, unpacked with dpkg-deb, never installed) with an initramfs of
busybox-static, the CAN, virtio and 9p modules and an init script. The VM mounts the host's root
read-only over 9p plus the build tree (and every --rw DIR) read-write at the same paths, chroots
into it, creates vcan0 with the host's `ip` and runs the command there: can-utils, python3 and the
build tree's binaries run unchanged. KVM is used when a short probe boots with it, else TCG.
The kernel, modules and initramfs are cached in build/canvm/ (keyed by the package version).
"""
import argparse
import fcntl
import hashlib
import json
import lzma
import os
import re
import shlex
import shutil
import signal
import socket
import stat
import struct
import subprocess
import sys
import tarfile
import tempfile
import threading
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Directories the VM mounts a tmpfs of its own on (the job script): a host path below one of
# them is not in the VM unless it is shared.
VM_OWN_DIRS = ("/tmp", "/run", "/var/tmp", "/dev/shm")


def hidden_in_vm(path):
    """True when @p path lies below a directory the VM has its own tmpfs on."""
    return any(path == d or path.startswith(d + "/") for d in VM_OWN_DIRS)
DEFAULT_CACHE = os.path.join(REPO, "build", "canvm")
KERNEL_META = "linux-image-amd64"
EXIT_SKIP = 77
EXIT_TIMEOUT = 124
EXIT_FAIL = 125
KVM_PROBE_TIMEOUT_S = 8.0
CACHE_LAYOUT = 2  # bump when what fetch_kernel() leaves in the cache changes
QEMU = os.environ.get("CANVM_QEMU", "qemu-system-x86_64")
BUSYBOX = "/bin/busybox"
NINEP = "trans=virtio,version=9p2000.L,msize=262144"
# Loaded in the VM in this order (modprobe pulls their dependencies, found from .modinfo).
VM_MODULES = ["virtio_pci", "9pnet_virtio", "9p", "can", "can_raw", "can_bcm", "can_gw",
              "can_dev", "vcan", "vxcan"]
# Directories of the kernel package searched first for those modules and their dependencies.
MODULE_DIRS = ("kernel/net/can/", "kernel/drivers/net/can/", "kernel/drivers/virtio/",
               "kernel/fs/9p/", "kernel/net/9p/", "kernel/fs/netfs/", "kernel/fs/fscache/")

# PID 1 of the VM. It talks to the host through the console (progress lines "canvm-init: ...")
# and the job directory (a 9p share): mounts, ifaces, run.sh in; stdout, stderr, rc, error out.
INIT_SCRIPT = r"""#!/bin/busybox sh
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
say() { echo "canvm-init: $*"; }
die() { say "FAIL: $*"; [ -f /job/ifaces ] && echo "$*" > /job/error; sync; reboot -f; }
say "kernel up"
for m in $(cat /etc/canvm-modules); do modprobe "$m" || die "modprobe $m"; done
case " $(cat /proc/cmdline) " in *" canvm.probe "*) say "PROBE-OK"; reboot -f;; esac
mkdir -p /job /host
mount -t 9p -o NINEP,cache=none job /job || die "mount of the job directory failed"
mount -t 9p -o NINEP,cache=loose,ro hostroot /host || die "mount of the host root failed"
mount -t proc proc /host/proc && mount -t sysfs sysfs /host/sys &&
    mount -t devtmpfs devtmpfs /host/dev && mkdir -p /host/dev/pts /host/dev/shm &&
    mount -t devpts devpts /host/dev/pts && mount -t tmpfs tmpfs /host/dev/shm &&
    mount -t tmpfs tmpfs /host/tmp && mount -t tmpfs tmpfs /host/run ||
    die "mounting proc, sys, dev, tmp in the host root failed"
[ -d /host/var/tmp ] && mount -t tmpfs tmpfs /host/var/tmp
while read -r tag dir opt; do
    mkdir -p "/host$dir" 2> /dev/null
    mount -t 9p -o NINEP,cache=none${opt:+,$opt} "$tag" "/host$dir" || die "mount of $dir failed"
done < /job/mounts
chroot /host ip link set lo up || die "ip link set lo up failed"
for i in $(cat /job/ifaces); do
    chroot /host ip link add dev "$i" type vcan && chroot /host ip link set up "$i" ||
        die "creating $i failed"
done
say "READY $(cat /job/ifaces)"
chroot /host /bin/sh -s < /job/run.sh > /job/stdout 2> /job/stderr
echo $? > /job/rc
sync
say "DONE"
reboot -f
""".replace("NINEP", NINEP)


def progress(args, msg):
    if not args.quiet:
        print(f"canvm: {msg}", file=sys.stderr, flush=True)


class Unavailable(Exception):
    """A path to SocketCAN cannot be used here; the message says why."""


# ---------------------------------------------------------------------------------------------
# Direct path: the host kernel has AF_CAN.


def af_can_error():
    """None when a CAN_RAW socket opens, else the error text."""
    if not hasattr(socket, "AF_CAN"):
        return "this Python has no socket.AF_CAN"
    try:
        socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
        return None
    except OSError as e:
        return f"socket(PF_CAN, SOCK_RAW, CAN_RAW): {e}"


def netns_prefix():
    """The unshare command that gives a new network namespace, with root in it."""
    unshare = shutil.which("unshare")
    if unshare is None:
        return None
    return [unshare, "--net"] + ([] if os.geteuid() == 0 else ["--map-root-user"])


def vcan_script(ifaces):
    """Shell lines that create and bring up the interfaces (and lo) in the current netns."""
    lines = ["ip link set lo up || exit 1"]
    for i in ifaces:
        q = shlex.quote(i)
        lines.append(f"ip link add dev {q} type vcan && ip link set up {q} || exit 1")
    return "\n".join(lines)


def direct_plan(ifaces):
    """How the direct path runs here: 'netns' (a new network namespace where the interfaces
    are created) or 'host' (the host's own interfaces, already up); raises Unavailable."""
    err = af_can_error()
    if err:
        raise Unavailable(f"host has no AF_CAN ({err})")
    if os.geteuid() == 0 and shutil.which("modprobe"):
        subprocess.run(["modprobe", "vcan"], capture_output=True)
    prefix = netns_prefix()
    why = "unshare not found"
    if prefix and shutil.which("ip"):
        r = subprocess.run(prefix + ["sh", "-c", vcan_script(ifaces)], capture_output=True,
                           text=True, timeout=30)
        if r.returncode == 0:
            return "netns"
        why = f"creating {' '.join(ifaces)} in a new network namespace failed: " + (
            r.stderr.strip() or f"exit {r.returncode}")
    down = [i for i in ifaces if not iface_up(i)]
    if not down:
        return "host"
    raise Unavailable(f"host has AF_CAN but {why}, and {', '.join(down)} is not up on the host")


def iface_up(name):
    try:
        with open(f"/sys/class/net/{name}/flags") as f:
            return int(f.read(), 16) & 1 == 1
    except (OSError, ValueError):
        return False


# ---------------------------------------------------------------------------------------------
# VM path: kernel package, modules, initramfs.


def sh(argv, **kw):
    return subprocess.run(argv, capture_output=True, text=True, **kw)


def resolve_kernel_package(cache):
    """(package, version) of the kernel image that linux-image-amd64 depends on. apt-cache
    takes a second or two here, so the answer is kept until apt's package lists change."""
    if shutil.which("apt-cache") is None:
        raise Unavailable("apt-cache not found (not a Debian system)")
    lists = "/var/lib/apt/lists"
    try:
        stamp = [os.stat(lists).st_mtime_ns] + sorted(
            e.stat().st_mtime_ns for e in os.scandir(lists) if e.is_file())
    except OSError:
        stamp = None
    memo = os.path.join(cache, "kernel-package.json")
    try:
        with open(memo) as f:
            m = json.load(f)
        if stamp is not None and m["stamp"] == stamp:
            return m["package"], m["version"]
    except (OSError, ValueError, KeyError):
        pass
    r = sh(["apt-cache", "show", "--no-all-versions", KERNEL_META])
    m = re.search(r"^Depends:.*?\b(linux-image-[^\s,]+)(?:\s*\(=\s*([^)\s]+)\))?", r.stdout, re.M)
    if not m:
        raise Unavailable(f"apt-cache show {KERNEL_META} names no kernel image "
                          f"(run apt-get update?): {r.stderr.strip()}")
    pkg, ver = m.group(1), m.group(2)
    if ver is None:
        r = sh(["apt-cache", "policy", pkg])
        v = re.search(r"^\s*Candidate:\s*(\S+)", r.stdout, re.M)
        if not v or v.group(1) == "(none)":
            raise Unavailable(f"apt-cache policy {pkg} gives no candidate version")
        ver = v.group(1)
    if stamp is not None:
        os.makedirs(cache, exist_ok=True)
        with open(memo, "w") as f:
            json.dump({"stamp": stamp, "package": pkg, "version": ver}, f)
    return pkg, ver


def kernel_cached(kdir):
    """Whether kdir holds a kernel unpacked by this version of canvm."""
    try:
        with open(os.path.join(kdir, "kernel.json")) as f:
            k = json.load(f)
        return k.get("layout") == CACHE_LAYOUT and k.get("wanted") == VM_MODULES
    except (OSError, ValueError):
        return False


def cached_kernels(cache):
    """Directories of kernels already unpacked in the cache, newest first."""
    out = []
    for d in os.listdir(cache) if os.path.isdir(cache) else []:
        p = os.path.join(cache, d)
        if d.startswith("linux-image-") and kernel_cached(p):
            out.append(p)
    return sorted(out, key=os.path.getmtime, reverse=True)


def modinfo(blob):
    """The .modinfo fields of a kernel module (ELF64 little endian) as a dict."""
    shoff, = struct.unpack_from("<Q", blob, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", blob, 0x3A)

    def sect(i):
        return struct.unpack_from("<IIQQQQ", blob, shoff + i * shentsize)
    stroff = sect(shstrndx)[4]
    for i in range(shnum):
        name_off, _, _, _, off, size = sect(i)
        end = blob.index(b"\0", stroff + name_off)
        if blob[stroff + name_off:end] == b".modinfo":
            fields = {}
            for item in blob[off:off + size].split(b"\0"):
                k, eq, v = item.partition(b"=")
                if eq:
                    fields.setdefault(k.decode(), v.decode())
            return fields
    raise ValueError("no .modinfo section")


def norm(mod):
    return mod.replace("-", "_")


def vmlinux_of(bzimage):
    """The ELF kernel inside an xz-compressed bzImage, or None. QEMU boots it through its PVH
    entry, skipping the decompression that takes seconds under TCG."""
    at = bzimage.find(b"\xfd7zXZ\x00")
    if at < 0:
        return None
    try:
        elf = lzma.LZMADecompressor(format=lzma.FORMAT_XZ).decompress(bzimage[at:])
    except lzma.LZMAError:
        return None
    return elf if elf[:4] == b"\x7fELF" and has_pvh_note(elf) else None


def has_pvh_note(elf):
    """Whether an ELF64 kernel has the XEN_ELFNOTE_PHYS32_ENTRY note (type 18) of owner Xen,
    the PVH entry point QEMU needs to boot it."""
    phoff, = struct.unpack_from("<Q", elf, 0x20)
    phentsize, phnum = struct.unpack_from("<HH", elf, 0x36)
    for i in range(phnum):
        ptype, _, off, _, _, filesz = struct.unpack_from("<IIQQQQ", elf, phoff + i * phentsize)
        pos, end = off, off + filesz
        while ptype == 4 and pos + 12 <= end:  # PT_NOTE
            namesz, descsz, ntype = struct.unpack_from("<III", elf, pos)
            name = elf[pos + 12:pos + 12 + namesz]
            if name == b"Xen\0" and ntype == 18:
                return True
            pos += 12 + (namesz + 3) // 4 * 4 + (descsz + 3) // 4 * 4
    return False


def unpack_kernel(deb, dest):
    """Writes into dest the kernel to boot (the ELF vmlinux when the bzImage holds one QEMU can
    boot, else vmlinuz) and the VM's modules with their dependencies, from the kernel package.
    Returns (uname -r, the kernel's file name, module names)."""
    def members(want):
        """Yields (tarinfo, bytes) of the package's members for which want(name) holds."""
        p = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", deb], stdout=subprocess.PIPE)
        try:
            with tarfile.open(fileobj=p.stdout, mode="r|") as tf:
                for ti in tf:
                    if ti.isfile() and want(ti.name):
                        yield ti, tf.extractfile(ti).read()
        finally:
            p.stdout.close()
            if p.wait() != 0:
                raise RuntimeError(f"dpkg-deb --fsys-tarfile {deb} failed")

    version = None
    vmlinuz = None
    found = {}  # module name -> (path below lib/modules/VERSION/, depends, blob or None)
    for ti, blob in members(lambda n: re.search(r"/boot/vmlinuz-|/lib/modules/.*\.ko$", n)):
        if "/boot/vmlinuz-" in ti.name:
            vmlinuz = blob
            version = ti.name.split("/boot/vmlinuz-")[1]
            continue
        rel = ti.name.split("/lib/modules/", 1)[1].split("/", 1)[1]
        info = modinfo(blob)
        deps = [norm(d) for d in info.get("depends", "").split(",") if d]
        found[norm(info["name"])] = (rel, deps, blob if rel.startswith(MODULE_DIRS) else None)
    if vmlinuz is None:
        raise RuntimeError(f"{deb} holds no /boot/vmlinuz-*")
    need, todo = set(), list(VM_MODULES)
    while todo:
        m = todo.pop()
        if m in need:
            continue
        if m not in found:
            raise RuntimeError(f"{deb} has no module {m} (needed for the VM)")
        need.add(m)
        todo += found[m][1]
    missing = {found[m][0] for m in need if found[m][2] is None}
    if missing:  # a dependency outside MODULE_DIRS: one more pass for it
        for ti, blob in members(lambda n: n.split("/lib/modules/", 1)[-1].split("/", 1)[-1]
                                in missing):
            m = norm(modinfo(blob)["name"])
            found[m] = found[m][:2] + (blob,)
    os.makedirs(dest)
    elf = vmlinux_of(vmlinuz)
    kernel = "vmlinux" if elf else "vmlinuz"
    with open(os.path.join(dest, kernel), "wb") as f:
        f.write(elf or vmlinuz)
    for m in sorted(need):
        path = os.path.join(dest, "modules", found[m][0])
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(found[m][2])
    return version, kernel, sorted(need)


def download(args, cache, dl):
    """(package, version, .deb path) of the current kernel package, downloaded into dl. When
    the download fails (lists older than the mirror), root updates apt's lists and resolves
    and downloads again."""
    for attempt in (1, 2):
        pkg, ver = resolve_kernel_package(cache)
        progress(args, f"downloading {pkg} {ver} (apt-get download, about 70 MB)")
        r = sh(["apt-get", "download", f"{pkg}={ver}"], cwd=dl)
        debs = [f for f in os.listdir(dl) if f.endswith(".deb")]
        if r.returncode == 0 and len(debs) == 1:
            return pkg, ver, os.path.join(dl, debs[0])
        if attempt == 1 and os.geteuid() == 0:
            progress(args, "apt-get download failed; apt-get update, then once more")
            sh(["apt-get", "update", "-q"])
    raise Unavailable(f"apt-get download {pkg}={ver} failed: {r.stderr.strip()[-500:]}")


def fetch_kernel(args, cache):
    """The cache directory of the current kernel package, downloaded and unpacked if needed."""
    try:
        pkg, ver = resolve_kernel_package(cache)
    except Unavailable as e:
        have = cached_kernels(cache)
        if have:
            progress(args, f"{e}; using the cached {os.path.basename(have[0])}")
            return have[0]
        raise
    kdir = os.path.join(cache, f"{pkg}_{ver}".replace(":", "%3a"))
    if kernel_cached(kdir):
        return kdir
    dl = tempfile.mkdtemp(prefix="dl-", dir=cache)
    try:
        t0 = time.monotonic()
        pkg, ver, deb = download(args, cache, dl)
        kdir = os.path.join(cache, f"{pkg}_{ver}".replace(":", "%3a"))
        t1 = time.monotonic()
        progress(args, f"downloaded {os.path.getsize(deb) / 1e6:.1f} MB in {t1 - t0:.1f} s; "
                 "unpacking the kernel and modules (dpkg-deb)")
        tmp = os.path.join(dl, "kernel")
        uname_r, kernel, mods = unpack_kernel(deb, tmp)
        with open(os.path.join(tmp, "kernel.json"), "w") as f:
            json.dump({"layout": CACHE_LAYOUT, "wanted": VM_MODULES, "package": pkg,
                       "version": ver, "deb": os.path.basename(deb),
                       "deb_bytes": os.path.getsize(deb), "uname_r": uname_r, "kernel": kernel,
                       "modules": mods, "download_s": round(t1 - t0, 2),
                       "unpack_s": round(time.monotonic() - t1, 2)}, f, indent=1)
        shutil.rmtree(kdir, ignore_errors=True)
        os.rename(tmp, kdir)
        progress(args, f"unpacked kernel {uname_r} ({kernel}) and {len(mods)} modules in "
                 f"{time.monotonic() - t1:.1f} s")
    finally:
        shutil.rmtree(dl, ignore_errors=True)
    for old in os.listdir(cache):  # keep only the current kernel
        if old.startswith("linux-image-") and os.path.join(cache, old) != kdir:
            shutil.rmtree(os.path.join(cache, old), ignore_errors=True)
    return kdir


def busybox_path():
    bb = BUSYBOX if os.path.exists(BUSYBOX) else shutil.which("busybox")
    if not bb:
        raise Unavailable("busybox not found (Debian package busybox-static)")
    with open(bb, "rb") as f:
        elf = f.read(1 << 16)
    phoff, = struct.unpack_from("<Q", elf, 0x20)
    phentsize, phnum = struct.unpack_from("<HH", elf, 0x36)
    if any(struct.unpack_from("<I", elf, phoff + i * phentsize)[0] == 3 for i in range(phnum)):
        raise Unavailable(f"{bb} is dynamically linked (PT_INTERP); install busybox-static")
    return bb


def cpio_newc(out, entries):
    """Writes a newc cpio archive; entries are (name, mode, data, rdev major, rdev minor)."""
    def put(ino, name, mode, data, rmaj=0, rmin=0):
        nb = name.encode() + b"\0"
        hdr = "070701" + "".join(f"{v:08X}" for v in (
            ino, mode, 0, 0, 2 if stat.S_ISDIR(mode) else 1, 0, len(data), 0, 0, rmaj, rmin,
            len(nb), 0))
        out.write(hdr.encode() + nb + b"\0" * (-(110 + len(nb)) % 4))
        out.write(data + b"\0" * (-len(data) % 4))
    for ino, (name, mode, data, rmaj, rmin) in enumerate(entries, 1):
        put(ino, name, mode, data, rmaj, rmin)
    put(0, "TRAILER!!!", 0, b"")


def build_initramfs(args, kdir):
    """The path of the initramfs for this kernel, built (and cached) when missing."""
    with open(os.path.join(kdir, "kernel.json")) as f:
        kinfo = json.load(f)
    bb = busybox_path()
    with open(bb, "rb") as f:
        bb_bytes = f.read()
    key = hashlib.sha256(INIT_SCRIPT.encode() + bb_bytes +
                         " ".join(VM_MODULES + kinfo["modules"]).encode()).hexdigest()[:16]
    path = os.path.join(kdir, f"initramfs-{key}.cpio")
    if os.path.exists(path):
        return path
    t0 = time.monotonic()
    progress(args, "building the initramfs (busybox-static, modules, init)")
    applets = sh([bb, "--list"]).stdout.split()
    uname_r = kinfo["uname_r"]
    with tempfile.TemporaryDirectory(dir=kdir) as stage:
        mroot = os.path.join(stage, "lib", "modules", uname_r)
        shutil.copytree(os.path.join(kdir, "modules"), mroot)
        r = sh([bb, "depmod", "-b", stage, uname_r])
        if r.returncode != 0 or not os.path.exists(os.path.join(mroot, "modules.dep")):
            raise RuntimeError(f"busybox depmod failed: {r.stderr}")
        files = []
        for d, dirs, names in os.walk(stage):
            dirs.sort()
            rel = os.path.relpath(d, stage)
            if rel != ".":
                files.append((rel, stat.S_IFDIR | 0o755, b"", 0, 0))
            for n in sorted(names):
                with open(os.path.join(d, n), "rb") as f:
                    files.append((os.path.join(rel, n), stat.S_IFREG | 0o644, f.read(), 0, 0))
    entries = [(d, stat.S_IFDIR | 0o755, b"", 0, 0)
               for d in ("bin", "dev", "proc", "sys", "etc", "tmp", "job", "host")]
    entries.append(("dev/console", stat.S_IFCHR | 0o600, b"", 5, 1))
    entries.append(("bin/busybox", stat.S_IFREG | 0o755, bb_bytes, 0, 0))
    entries += [(f"bin/{a}", stat.S_IFLNK | 0o777, b"busybox", 0, 0)
                for a in applets if a != "busybox"]
    entries.append(("init", stat.S_IFREG | 0o755, INIT_SCRIPT.encode(), 0, 0))
    entries.append(("etc/canvm-modules", stat.S_IFREG | 0o644,
                    ("\n".join(VM_MODULES) + "\n").encode(), 0, 0))
    entries += files
    tmp = path + ".tmp"
    with open(tmp, "wb") as out:
        cpio_newc(out, entries)
    os.rename(tmp, path)
    for old in os.listdir(kdir):
        if old.startswith("initramfs-") and os.path.join(kdir, old) != path:
            os.remove(os.path.join(kdir, old))
    progress(args, f"initramfs {os.path.getsize(path) / 1e6:.1f} MB built in "
             f"{time.monotonic() - t0:.1f} s")
    return path


class Lock:
    """An exclusive lock on the cache, so parallel runs download and build once."""

    def __init__(self, cache):
        os.makedirs(cache, exist_ok=True)
        self.f = open(os.path.join(cache, "lock"), "w")

    def __enter__(self):
        fcntl.flock(self.f, fcntl.LOCK_EX)
        return self

    def __exit__(self, *exc):
        fcntl.flock(self.f, fcntl.LOCK_UN)
        self.f.close()


def vm_tools_error():
    """None when QEMU, busybox-static, apt-get and dpkg-deb are here, else what is missing."""
    missing = [f"{t} (Debian package {pkg})" for t, pkg in (
        (QEMU, "qemu-system-x86"), ("dpkg-deb", "dpkg"), ("apt-get", "apt"))
        if shutil.which(t) is None]
    if missing:
        return f"not found: {', '.join(missing)}"
    try:
        busybox_path()
    except Unavailable as e:
        return str(e)
    return None


def prepare(args):
    """(kernel dir, initramfs path, accelerator, why that one): the kernel downloaded, the
    initramfs built and KVM probed when not done before."""
    err = vm_tools_error()
    if err:
        raise Unavailable(err)
    with Lock(args.cache):
        kdir = fetch_kernel(args, args.cache)
        initramfs = build_initramfs(args, kdir)
        return (kdir, initramfs) + choose_accel(args, kdir, initramfs)


# ---------------------------------------------------------------------------------------------
# Running QEMU.


def set_pdeathsig():
    """In the child: die with SIGKILL when canvm dies, so no QEMU outlives it."""
    import ctypes
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def qemu_argv(kdir, initramfs, accel, append, shares, smp=1, mem_mb=1024):
    with open(os.path.join(kdir, "kernel.json")) as f:
        kernel = os.path.join(kdir, json.load(f)["kernel"])
    argv = [QEMU, "-machine", "q35", "-accel", accel, "-cpu", "host" if accel == "kvm" else "max",
            "-m", str(mem_mb), "-smp", str(smp), "-nodefaults", "-no-user-config",
            "-display", "none", "-vga", "none", "-serial", "stdio", "-monitor", "none",
            "-no-reboot", "-kernel", kernel, "-initrd", initramfs,
            "-append", "console=ttyS0 panic=-1 quiet loglevel=3 " + append]
    for tag, path, ro in shares:
        argv += ["-virtfs", f"local,path={path},mount_tag={tag},security_model=none,"
                 f"multidevs=remap{',readonly=on' if ro else ''}"]
    return argv


class Qemu:
    """A QEMU process whose console lines are collected by a thread; killed on close()."""

    def __init__(self, argv, on_line=None):
        self.lines = []
        self.on_line = on_line
        self.t0 = time.monotonic()
        self.p = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, preexec_fn=set_pdeathsig,
                                  start_new_session=True)
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for raw in self.p.stdout:
            line = raw.decode(errors="replace").rstrip("\r\n")
            self.lines.append(line)
            if self.on_line:
                self.on_line(line, time.monotonic() - self.t0)

    def close(self):
        if self.p.poll() is None:
            try:
                os.killpg(self.p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        self.p.wait()
        self.reader.join(timeout=5)

    def tail(self, n=30):
        return "\n".join(self.lines[-n:])


def boot_id():
    """This host boot's id (changes at every boot)."""
    try:
        with open("/proc/sys/kernel/random/boot_id") as f:
            return f.read().strip().replace("-", "")
    except OSError:
        return "unknown"


def kvm_usable(args, kdir, initramfs):
    """(True/False, why): whether QEMU boots the VM with KVM here; cached per host boot."""
    try:
        fd = os.open("/dev/kvm", os.O_RDWR)
        os.close(fd)
    except OSError as e:
        return False, f"/dev/kvm: {e.strerror}"
    qver = sh([QEMU, "--version"]).stdout.split("\n")[0]
    key = f"{boot_id()} {qver}"
    memo = os.path.join(args.cache, "kvm-probe.json")
    try:
        with open(memo) as f:
            m = json.load(f)
        if m.get("key") == key:
            return m["ok"], m["why"]
    except (OSError, ValueError):
        pass
    progress(args, f"/dev/kvm opens; probing KVM (boot to init, at most "
                   f"{KVM_PROBE_TIMEOUT_S:.0f} s)")
    q = Qemu(qemu_argv(kdir, initramfs, "kvm", "canvm.probe", []))
    try:
        q.p.wait(timeout=KVM_PROBE_TIMEOUT_S)
        dt = time.monotonic() - q.t0
    except subprocess.TimeoutExpired:
        dt = None
    q.close()
    if dt is None:
        ok, why = False, f"KVM probe did not finish in {KVM_PROBE_TIMEOUT_S:.0f} s"
    elif any("PROBE-OK" in line for line in q.lines):
        ok, why = True, f"KVM probe booted in {dt:.1f} s"
    else:
        last = [line for line in q.lines if line.strip()][-1:] or [f"exit {q.p.returncode}"]
        ok, why = False, f"KVM probe failed: {last[0][:200]}"
    with open(memo, "w") as f:
        json.dump({"key": key, "ok": ok, "why": why}, f)
    return ok, why


def choose_accel(args, kdir, initramfs):
    if args.accel != "auto":
        return args.accel, "as asked (--accel)"
    ok, why = kvm_usable(args, kdir, initramfs)
    return ("kvm", why) if ok else ("tcg", why)


def job_script(cmd):
    """The shell script run in the VM's chroot (read from its stdin): the caller's environment,
    directory and command, the command's stdin /dev/null."""
    lines = []
    for k, v in sorted(os.environ.items()):
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", k) and k not in ("PWD", "OLDPWD", "SHLVL",
                                                                      "_"):
            lines.append(f"export {k}={shlex.quote(v)}")
    cwd = os.getcwd()
    lines.append(f"cd {shlex.quote(cwd)} || {{ echo 'canvm: the current directory is not in the "
                 "VM (its /tmp, /run, /var/tmp and /dev/shm are its own): run from the build "
                 f"tree or share it with --rw' >&2; exit {EXIT_FAIL}; }}")
    lines.append(f"exec /bin/sh -c {shlex.quote(cmd)} < /dev/null")
    return "\n".join(lines) + "\n"


class Pump:
    """Copies what the VM appends to a job file to one of canvm's own streams."""

    def __init__(self, path, stream):
        self.path, self.stream, self.pos = path, stream, 0

    def run(self):
        try:
            with open(self.path, "rb") as f:
                f.seek(self.pos)
                data = f.read()
        except OSError:
            return
        if data:
            self.pos += len(data)
            self.stream.write(data)
            self.stream.flush()


def run_vm(args, cmd, deadline):
    kdir, initramfs, accel, why = prepare(args)
    jobs = os.path.join(args.cache, "jobs")
    os.makedirs(jobs, exist_ok=True)
    boot = boot_id()[:8]
    for old in os.listdir(jobs):  # left by a canvm that was killed (SIGKILL)
        b, pid = (old.split("-") + ["", ""])[:2]
        age = time.time() - os.path.getmtime(os.path.join(jobs, old))
        if (b == boot and not os.path.exists(f"/proc/{pid}")) or (b != boot and age > 86400):
            shutil.rmtree(os.path.join(jobs, old), ignore_errors=True)
    job = tempfile.mkdtemp(prefix=f"{boot}-{os.getpid()}-", dir=jobs)
    shares = [("hostroot", "/", True), ("job", job, False)]
    rw = []
    if hidden_in_vm(REPO):  # e.g. a clone in mktemp -d: the VM's own /tmp would hide it
        shares.append(("repo", REPO, True))
        rw.append(f"repo {REPO} ro")
    for i, d in enumerate(dict.fromkeys([args.build_dir] + args.rw)):
        shares.append((f"rw{i}", d, False))
        rw.append(f"rw{i} {d}")
    with open(os.path.join(job, "mounts"), "w") as f:
        f.write("".join(line + "\n" for line in rw))
    with open(os.path.join(job, "ifaces"), "w") as f:
        f.write(" ".join(args.iface) + "\n")
    with open(os.path.join(job, "run.sh"), "w") as f:
        f.write(job_script(cmd))
    for n in ("stdout", "stderr"):
        open(os.path.join(job, n), "wb").close()
    pumps = [Pump(os.path.join(job, "stdout"), sys.stdout.buffer),
             Pump(os.path.join(job, "stderr"), sys.stderr.buffer)]
    progress(args, f"booting {os.path.basename(kdir)} under {accel.upper()} ({why})")

    def on_line(line, t):
        if args.verbose:
            print(f"canvm[vm {t:5.1f}s]: {line}", file=sys.stderr, flush=True)
        elif line.startswith("canvm-init: READY"):
            progress(args, f"{' '.join(args.iface)} up in the VM after {t:.1f} s; running")
        elif line.startswith("canvm-init: FAIL"):
            progress(args, line)
    q = Qemu(qemu_argv(kdir, initramfs, accel, "", shares, args.smp, args.mem), on_line)
    try:
        while q.p.poll() is None:
            for p in pumps:
                p.run()
            if time.monotonic() > deadline:
                q.close()
                for p in pumps:
                    p.run()
                print(f"canvm: timed out after {args.timeout:g} s; QEMU killed. Console:\n"
                      f"{q.tail()}", file=sys.stderr)
                return EXIT_TIMEOUT
            time.sleep(0.05)
        q.close()
        for p in pumps:
            p.run()
        rc_path, err_path = os.path.join(job, "rc"), os.path.join(job, "error")
        if os.path.exists(rc_path):
            with open(rc_path) as f:
                rc = int(f.read().strip())
            progress(args, f"exit {rc}, {time.monotonic() - q.t0:.1f} s after boot start")
            return rc
        why = open(err_path).read().strip() if os.path.exists(err_path) else \
            f"the VM stopped (QEMU exit {q.p.returncode}) without a result"
        print(f"canvm: {why}. Console:\n{q.tail()}", file=sys.stderr)
        return EXIT_FAIL
    finally:
        q.close()
        if not args.keep_job:
            shutil.rmtree(job, ignore_errors=True)
        else:
            progress(args, f"job directory kept: {job}")


def run_direct(args, plan, cmd, deadline):
    if plan == "netns":
        argv = netns_prefix() + ["sh", "-c", vcan_script(args.iface) + "\nexec /bin/sh -c " +
                                 shlex.quote(cmd)]
        progress(args, f"running directly in a new network namespace with "
                       f"{' '.join(args.iface)}")
    else:
        argv = ["/bin/sh", "-c", cmd]
        progress(args, f"running directly on the host's {' '.join(args.iface)}")
    p = subprocess.Popen(argv, stdin=subprocess.DEVNULL, preexec_fn=set_pdeathsig,
                         start_new_session=True)
    try:
        return p.wait(timeout=max(0.0, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        print(f"canvm: timed out after {args.timeout:g} s; command killed", file=sys.stderr)
        return EXIT_TIMEOUT
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


# ---------------------------------------------------------------------------------------------
# Commands.


def cmd_check(args):
    print(f"interfaces: {' '.join(args.iface)}")
    ok = {}
    try:
        plan = direct_plan(args.iface)
        ok["direct"] = True
        where = "in a new network namespace" if plan == "netns" else "on the host"
        print(f"direct: available ({where} with {' '.join(args.iface)})")
    except Unavailable as e:
        print(f"direct: unavailable: {e}")
    err = vm_tools_error()
    if not err:
        try:
            pkg, ver = resolve_kernel_package(args.cache)
            key = f"{pkg}_{ver}".replace(":", "%3a")
            state = "cached" if kernel_cached(os.path.join(args.cache, key)) else "to download"
            print(f"vm: available: {QEMU}, kernel {pkg} {ver} ({state} in {args.cache})")
            ok["vm"] = True
        except Unavailable as e:
            have = cached_kernels(args.cache)
            if have:
                print(f"vm: available: {os.path.basename(have[0])} cached ({e})")
                ok["vm"] = True
            else:
                err = str(e)
    if err:
        print(f"vm: unavailable: {err}")
    else:
        memo = os.path.join(args.cache, "kvm-probe.json")
        try:
            with open(memo) as f:
                m = json.load(f)
            print(f"vm: accelerator {'kvm' if m['ok'] else 'tcg'} ({m['why']}; probed once per "
                  "host boot)")
        except (OSError, ValueError, KeyError):
            print("vm: accelerator not probed yet (the first run probes KVM, else uses TCG)")
    allowed = ("direct", "vm") if args.mode == "auto" else (args.mode,)
    path = next((m for m in allowed if ok.get(m)), None)
    print(f"path: {path or 'none (canvm run exits 77: SocketCAN tests are skipped)'}")
    return 0 if path else EXIT_SKIP


def cmd_prepare(args):
    try:
        kdir, initramfs, accel, why = prepare(args)
    except Unavailable as e:
        print(f"canvm: VM unavailable: {e}", file=sys.stderr)
        return EXIT_SKIP
    print(f"kernel: {kdir}\ninitramfs: {initramfs}\naccelerator: {accel} ({why})")
    return 0


def cmd_run(args):
    words = args.command
    if words and words[0] == "--":
        words = words[1:]
    if not words:
        print("canvm: run needs a command after --", file=sys.stderr)
        return 2
    cmd = shlex.join(words) if args.argv else " ".join(words)
    deadline = time.monotonic() + args.timeout
    reasons = []
    if args.mode in ("auto", "direct"):
        try:
            return run_direct(args, direct_plan(args.iface), cmd, deadline)
        except Unavailable as e:
            reasons.append(f"direct: {e}")
    if args.mode in ("auto", "vm"):
        try:
            return run_vm(args, cmd, deadline)
        except Unavailable as e:
            reasons.append(f"vm: {e}")
    print(f"canvm: SKIPPED: no SocketCAN here ({'; '.join(reasons)})", file=sys.stderr)
    return EXIT_SKIP


def main():
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--mode", choices=("auto", "direct", "vm"),
                        default=os.environ.get("CANVM_MODE", "auto"),
                        help="auto (default, or $CANVM_MODE): direct when the host can, else vm")
    common.add_argument("--iface", action="append", metavar="NAME",
                        help="vcan interface to create and bring up (repeatable; default vcan0)")
    common.add_argument("--accel", choices=("auto", "kvm", "tcg"), default="auto",
                        help="VM accelerator; auto probes KVM once per host boot, else TCG")
    common.add_argument("--cache", default=os.environ.get("CANVM_CACHE", DEFAULT_CACHE),
                        help="cache for kernel and initramfs (default build/canvm, or "
                             "$CANVM_CACHE)")
    common.add_argument("-q", "--quiet", action="store_true", help="no progress lines on stderr")
    common.add_argument("-v", "--verbose", action="store_true",
                        help="copy the VM's console to stderr")
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="sub", required=True, metavar="{check,prepare,run}")
    sub.add_parser("check", parents=[common],
                   help="say which path to SocketCAN is available and why (exit 0, or 77 "
                        "when none)")
    sub.add_parser("prepare", parents=[common],
                   help="download the kernel, build the initramfs, probe KVM")
    r = sub.add_parser("run", parents=[common],
                       usage="%(prog)s [options] -- CMD [ARGS...]",
                       help="run CMD ARGS... as one shell command line with the interfaces up")
    r.add_argument("--argv", action="store_true",
                   help="run the words after -- as one argument vector, each word quoted, "
                        "instead of joining them into a shell command line")
    r.add_argument("--timeout", type=float, default=600,
                   help="seconds for the whole run, boot included (default 600); then the "
                        "command or QEMU is killed and canvm exits 124")
    r.add_argument("--build-dir", default=os.path.join(REPO, "build"),
                   help="directory the VM may write, at the same path (default the build tree)")
    r.add_argument("--rw", action="append", default=[], metavar="DIR",
                   help="another host directory the VM may write (repeatable); the rest of the "
                        "host's files are read-only in the VM, and /tmp is the VM's own")
    r.add_argument("--smp", type=int, default=1, choices=range(1, 9), metavar="N",
                   help="virtual CPUs of the VM (default 1; under TCG more rarely help)")
    r.add_argument("--mem", type=int, default=1024, metavar="MB",
                   help="memory of the VM in MB (default 1024)")
    r.add_argument("--keep-job", action="store_true",
                   help="keep the VM's job directory (build/canvm/jobs/...) for inspection")
    r.add_argument("command", nargs=argparse.REMAINDER, help="-- CMD ARGS...")
    args = ap.parse_args()
    args.iface = args.iface or ["vcan0"]
    for name in args.iface:
        if not re.fullmatch(r"[A-Za-z0-9_.-]{1,15}", name):
            ap.error(f"--iface {name!r}: an interface name is 1 to 15 letters, digits, '_', "
                     "'.' or '-'")
    args.cache = os.path.abspath(args.cache)
    if args.sub == "run":
        if args.timeout <= 0:
            r.error(f"--timeout {args.timeout:g}: must be more than 0 seconds")
        if not 256 <= args.mem <= 65536:
            r.error(f"--mem {args.mem}: must be 256 to 65536 MB")
        args.build_dir = os.path.abspath(args.build_dir)
        args.rw = [os.path.abspath(d) for d in args.rw]
        for d in [args.build_dir] + args.rw:
            os.makedirs(d, exist_ok=True)
    for s in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, lambda n, f: sys.exit(128 + n))  # unwinds: QEMU killed in finally
    try:
        return {"check": cmd_check, "prepare": cmd_prepare, "run": cmd_run}[args.sub](args)
    except KeyboardInterrupt:
        return 130
    except (RuntimeError, OSError, ValueError, subprocess.SubprocessError) as e:
        print(f"canvm: error: {e}", file=sys.stderr)
        return EXIT_FAIL


if __name__ == "__main__":
    sys.exit(main())
