"""fnet-server over TLS (--tls-cert, --tls-key), with a certificate made here by the openssl CLI
for 127.0.0.1 (never committed). On loopback: the TCP API answers TLS clients (the Python client
given an SSLContext, fnetctl --tls-ca) and a client that does not trust the certificate fails its
handshake; plain text on the TLS port is refused without harm; a connection that never completes
its handshake holds its slot no longer than --first-request-timeout; the dashboard serves its page
over https and the API over wss. In a network namespace (needs root; skipped otherwise): a
non-loopback --bind without TLS is refused at start, and without --token-file the server makes
DATA_DIR/token (mode 0600), prints where it is, and asks for it. The commands of deploy/README.md's
"Off loopback" are the ones run here.

usage: tls_test.py SOURCE_DIR BUILD_DIR WORK_DIR DOMAIN   (exit 77: the namespace part could not run)
"""

import json
import os
import re
import shutil
import socket
import ssl
import stat
import subprocess
import sys
import time
import urllib.request

NS_IP = "10.234.0.1"


def readme_commands(source_dir):
    """The shell lines of deploy/README.md's "Off loopback" block, in order."""
    text = open(os.path.join(source_dir, "deploy", "README.md")).read()
    block = re.search(r"### Off loopback.*?```sh\n(.*?)```", text, re.S)
    assert block, "deploy/README.md has no sh block under '### Off loopback'"
    return [l for l in block.group(1).splitlines() if l.strip() and not l.startswith("#")]


def make_certificate(source_dir, work, host):
    """cert.pem and key.pem in `work` for `host`, by deploy/README.md's openssl command."""
    command = next(c for c in readme_commands(source_dir) if c.startswith("openssl "))
    command = command.replace("HOST", host)
    subprocess.run(command, shell=True, cwd=work, check=True, capture_output=True, timeout=60)
    return os.path.join(work, "cert.pem"), os.path.join(work, "key.pem")


def start_server(prefix, server, flags, work, name):
    out_path, err_path = os.path.join(work, name + ".out"), os.path.join(work, name + ".err")
    process = subprocess.Popen(prefix + [server] + flags, stdout=open(out_path, "w"), stderr=open(err_path, "w"))
    deadline = time.monotonic() + 30
    while "listening on" not in open(out_path).read():
        assert process.poll() is None, open(err_path).read()
        assert time.monotonic() < deadline, "fnet-server did not start"
        time.sleep(0.1)
    out = open(out_path).read()
    api = int(re.search(r"listening on \S+:(\d+)", out).group(1))
    http = re.search(r"dashboard on https?://\S+:(\d+)/", out)
    return process, out, api, int(http.group(1)) if http else None


def stop(process):
    process.terminate()
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def is_open(s):
    """Whether the peer has not closed socket s (nothing to read yet, no end of stream)."""
    s.setblocking(False)
    try:
        return s.recv(1, socket.MSG_PEEK) != b""
    except BlockingIOError:
        return True
    except OSError:
        return False
    finally:
        s.setblocking(True)


def loopback_checks(source_dir, build_dir, work, domain):
    sys.path.insert(0, os.path.join(source_dir, "client", "python"))
    sys.path.insert(0, os.path.join(source_dir, "tests", "e2e"))
    import fnet
    from websocket_client import WebSocket

    server = os.path.join(build_dir, "bin", "fnet-server")
    fnetctl = os.path.join(build_dir, "bin", "fnetctl")
    cert, key = make_certificate(source_dir, work, "127.0.0.1")
    trusted = ssl.create_default_context(cafile=cert)
    flags = ["--data-dir", os.path.join(work, "data"), "--port", "0", "--http-port", "0", "--domain", str(domain),
             "--threads", "1", "--tls-cert", cert, "--tls-key", key, "--first-request-timeout", "3",
             "--max-connections", "2"]
    process, out, api, http = start_server([], server, flags, work, "loopback")
    try:
        assert "(TLS)" in out and f"https://127.0.0.1:{http}/" in out, out

        assert fnet.Client("127.0.0.1", api, tls=trusted).runs() == []
        ok = subprocess.run([fnetctl, "--port", str(api), "--tls-ca", cert, "status"], capture_output=True,
                            text=True, timeout=60)
        assert ok.returncode == 0 and "ingest" in ok.stdout, (ok.returncode, ok.stdout, ok.stderr)
        untrusting = subprocess.run([fnetctl, "--port", str(api), "--tls", "status"], capture_output=True, text=True,
                                    timeout=60)
        assert untrusting.returncode == 3 and "TLS handshake" in untrusting.stderr, untrusting.stderr
        try:
            fnet.Client("127.0.0.1", api, tls=True).runs()
            raise AssertionError("the Python client trusted a certificate no authority signed")
        except ssl.SSLCertVerificationError:
            pass
        print("ok: the TLS API answers fnet.Client(tls=SSLContext) and fnetctl --tls-ca; a client that does not "
              "trust the certificate fails its handshake")

        with socket.create_connection(("127.0.0.1", api), timeout=10) as s:
            s.sendall(b'{"jsonrpc":"2.0","id":1,"method":"runs.list"}\n')
            got = s.recv(4096)
            assert b"runs" not in got, got
        assert process.poll() is None
        assert fnet.Client("127.0.0.1", api, tls=trusted).status()["ingest"]
        print("ok: plain text on the TLS port is answered with no result; the server serves on")

        # Two silent connections fill --max-connections 2; each is closed at its handshake's deadline.
        # The deadline is 3 s so that a slow (sanitized, loaded) server still refuses the third
        # connection while the two are held; that they are still open afterwards is checked.
        # A slot the server has not yet freed from an earlier client refuses (closes) a silent one:
        # both must be seen held before the third is tried.
        for _ in range(20):
            silent = [socket.create_connection(("127.0.0.1", api), timeout=10) for _ in range(2)]
            opened = time.monotonic()
            time.sleep(0.3)
            if all(is_open(s) for s in silent):
                break
            for s in silent:
                s.close()
        else:
            raise AssertionError("two silent connections were never both held")
        try:
            fnet.Client("127.0.0.1", api, tls=trusted, timeout=1.5).runs()
            raise AssertionError("a third connection was served beside two held ones")
        except (OSError, ConnectionError):
            pass
        assert time.monotonic() - opened < 3, "the third connection was not refused within the deadline"
        assert all(is_open(s) for s in silent), "a silent connection was closed before its deadline"
        for s in silent:
            assert s.recv(1) == b"", "the server kept a connection that never completed its handshake"
            s.close()
        held = time.monotonic() - opened
        assert held < 5, held
        assert fnet.Client("127.0.0.1", api, tls=trusted).runs() == []
        print(f"ok: connections that never complete the handshake are closed at its deadline ({held:.1f} s), "
              "their slots free again")

        page = urllib.request.urlopen(f"https://127.0.0.1:{http}/", context=trusted, timeout=10)
        assert page.status == 200 and b"<html" in page.read()
        ws = WebSocket("127.0.0.1", http, origin=f"https://127.0.0.1:{http}", tls=trusted)
        answer = ws.call("runs.list")
        assert answer["result"] == {"runs": []}, answer
        ws.close()
        with socket.create_connection(("127.0.0.1", http), timeout=10) as s:
            s.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            assert b"<html" not in s.recv(4096)
        with socket.create_connection(("127.0.0.1", http), timeout=10) as s:
            started = time.monotonic()
            assert s.recv(1) == b"", "the dashboard kept a connection that never completed its handshake"
            held = time.monotonic() - started
            assert held < 5, held
        assert process.poll() is None
        print("ok: the dashboard serves its page over https and the API over wss, nothing over plain HTTP; a silent "
              f"connection is closed at its handshake's deadline ({held:.1f} s)")
    finally:
        stop(process)


def namespace_checks(source_dir, build_dir, work, domain):
    """fnet-server on NS_IP, an address of the loopback device of a namespace of its own."""
    sys.path.insert(0, os.path.join(source_dir, "client", "python"))
    import fnet

    server = os.path.join(build_dir, "bin", "fnet-server")
    fnetctl = os.path.join(build_dir, "bin", "fnetctl")
    ns = f"ft{os.getpid()}"
    if subprocess.run(["ip", "netns", "add", ns], capture_output=True).returncode != 0:
        print("cannot create a network namespace: the off-loopback part is skipped")
        return 77
    process = None
    try:
        subprocess.run(["ip", "-n", ns, "link", "set", "lo", "up"], check=True)
        subprocess.run(["ip", "-n", ns, "addr", "add", f"{NS_IP}/32", "dev", "lo"], check=True)
        inside = ["ip", "netns", "exec", ns]
        cert, key = make_certificate(source_dir, work, NS_IP)
        data = os.path.join(work, "ns-data")
        base = ["--data-dir", data, "--bind", NS_IP, "--port", "7707", "--domain", str(domain), "--threads", "1"]
        plain = subprocess.run(inside + [server] + base, capture_output=True, text=True, timeout=60)
        assert plain.returncode == 2 and "--tls-cert" in plain.stderr and NS_IP in plain.stderr, plain.stderr
        print(f"ok: --bind {NS_IP} without TLS is refused at start: {plain.stderr.strip()}")

        # deploy/README.md's fnet-server line, as written there.
        line = next(c for c in readme_commands(source_dir) if c.startswith("fnet-server "))
        flags = line.split()[1:]
        flags = [{"HOST": NS_IP, "DATA_DIR": data, "cert.pem": cert, "key.pem": key}.get(f, f) for f in flags]
        assert flags == ["--bind", NS_IP, "--data-dir", data, "--tls-cert", cert, "--tls-key", key], flags
        process, out, api, _ = start_server(inside, server, flags + ["--domain", str(domain), "--threads", "1"],
                                            work, "ns")
        token_file = os.path.join(data, "token")
        assert token_file in out, out
        mode = stat.S_IMODE(os.stat(token_file).st_mode)
        assert mode == 0o600, oct(mode)
        token = open(token_file).read().strip()
        assert len(token) >= 32 and re.fullmatch(r"[A-Za-z0-9_-]+", token), token
        print(f"ok: without --token-file the server made {token_file} (mode {oct(mode)}, {len(token)} characters)")

        client = ("import fnet, ssl, sys; c = ssl.create_default_context(cafile=sys.argv[3]); "
                  "print(fnet.Client(sys.argv[1], int(sys.argv[2]), tls=c, token=sys.argv[4] or None).runs())")
        env = dict(os.environ, PYTHONPATH=os.path.join(source_dir, "client", "python"))
        env.pop("FNET_TOKEN", None)
        served = subprocess.run(inside + [sys.executable, "-c", client, NS_IP, str(api), cert, token], env=env,
                                capture_output=True, text=True, timeout=60)
        assert served.returncode == 0 and served.stdout.strip() == "[]", served.stderr
        refused = subprocess.run(inside + [sys.executable, "-c", client, NS_IP, str(api), cert, ""], env=env,
                                 capture_output=True, text=True, timeout=60)
        assert refused.returncode != 0 and "-32007" in refused.stderr, refused.stderr
        readme_fnetctl = next(c for c in readme_commands(source_dir) if c.startswith("fnetctl "))
        readme_fnetctl = readme_fnetctl.replace("HOST", NS_IP).replace("DATA_DIR", data).split()
        with_file = subprocess.run(inside + [fnetctl] + readme_fnetctl[1:], cwd=work, env=env, capture_output=True,
                                   text=True, timeout=60)
        assert with_file.returncode == 0 and "ingest" in with_file.stdout, with_file.stderr
        print("ok: the made token is asked for: served with it (Python, deploy/README.md's fnetctl line), refused without")
        stop(process)
        process = None

        # On restart the token is kept; a token file others may read is refused.
        process, out, api, _ = start_server(inside, server, flags + ["--domain", str(domain)], work, "ns2")
        assert open(token_file).read().strip() == token
        stop(process)
        process = None
        os.chmod(token_file, 0o644)
        loose = subprocess.run(inside + [server] + flags + ["--domain", str(domain)], capture_output=True, text=True,
                               timeout=60)
        assert loose.returncode == 1 and "0644" in loose.stderr, loose.stderr
        print("ok: the token is kept across a restart; a token file others may read is refused")
        return 0
    finally:
        if process:
            stop(process)
        subprocess.run(["ip", "netns", "del", ns], capture_output=True)


def main():
    source_dir, build_dir, work = (os.path.abspath(a) for a in sys.argv[1:4])
    domain = int(sys.argv[4])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    loopback_checks(source_dir, build_dir, work, domain)
    return namespace_checks(source_dir, build_dir, work, domain)


if __name__ == "__main__":
    sys.exit(main())
