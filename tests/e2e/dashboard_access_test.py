"""Who may use fnet-server beyond loopback, on addresses inside two network namespaces the test
creates (a server host and a client host joined by a veth pair, as tests/e2e/multihost_test.sh
makes its hosts; DDS domain 88). fnet-server refuses to listen on a non-loopback address without
TLS (tests/e2e/tls_test.py tests TLS itself; here a certificate made by openssl for SERVER_IP, and
every client speaks TLS); with --token-file, a connection that does not present the token gets error -32007 and is
closed before any method runs — on the TCP API (raw, fnetctl, the Python client) and on the
dashboard (401 for the page and the WebSocket) — while fnetctl --token-file, FNET_TOKEN,
fnet.Client(token=...) and the page opened once with ?token= are served.

usage: dashboard_access_test.py SOURCE_DIR BUILD_DIR WORK_DIR   (exit 77: no network namespaces)
"""

import json
import os
import shutil
import socket
import ssl
import subprocess
import sys
import time
import urllib.error
import urllib.request

SERVER_IP, CLIENT_IP = "10.233.0.1", "10.233.0.2"
API_PORT, HTTP_PORT, DOMAIN = 7707, 7708, 88
TOKEN = "e2e-dashboard-token-0123456789abcdef"


def client_checks(source_dir, build_dir, token_file):
    """Run inside the client namespace: everything a host of the network sees of the server."""
    sys.path.insert(0, os.path.join(source_dir, "client", "python"))
    sys.path.insert(0, os.path.join(source_dir, "tests", "e2e"))
    import fnet
    from websocket_client import HandshakeRefused, WebSocket

    fnetctl = os.path.join(build_dir, "bin", "fnetctl")
    env = {k: v for k, v in os.environ.items() if k != "FNET_TOKEN"}
    cert = os.path.join(os.path.dirname(token_file), "cert.pem")
    tls = ssl.create_default_context(cafile=cert)

    def connect():
        return tls.wrap_socket(socket.create_connection((SERVER_IP, API_PORT), timeout=10), server_hostname=SERVER_IP)

    # The TCP API, raw: the first request is not auth, so it is refused and the connection closed.
    with connect() as s:
        s.sendall(b'{"jsonrpc":"2.0","id":1,"method":"runs.list"}\n{"jsonrpc":"2.0","id":2,"method":"runs.list"}\n')
        f = s.makefile()
        refusal = json.loads(f.readline())
        assert refusal["error"]["code"] == -32007, refusal
        assert refusal["id"] == 1, refusal
        assert f.readline() == "", "the connection stayed open after the refusal"
    print("ok: the TCP API refuses a connection without the token, before any method")

    # proto/api.md's exchanges of the auth request, as written there (its token is not ours).
    doc = open(os.path.join(source_dir, "proto", "api.md")).read().splitlines()
    example = {k: json.loads(next(l for l in doc if l.startswith(k + ":")).split(":", 1)[1])
               for k in ("first request", "its answer", "a wrong token")}
    for token, expected in ((TOKEN, example["its answer"]), (None, example["a wrong token"])):
        request = dict(example["first request"])
        if token:
            request["params"] = {"token": token}
        with connect() as s:
            s.sendall((json.dumps(request) + "\n").encode())
            answer = json.loads(s.makefile().readline())
        assert answer == expected, (answer, expected)
    print("ok: proto/api.md's auth exchanges, the right token and a wrong one")

    # fnetctl: without the token it fails naming the auth request; with --token-file or FNET_TOKEN it works.
    bare = subprocess.run([fnetctl, "--host", SERVER_IP, "--port", str(API_PORT), "--tls-ca", cert, "runs"], env=env,
                          capture_output=True, text=True, timeout=60)
    assert bare.returncode == 5 and "token" in bare.stderr, (bare.returncode, bare.stderr)
    with_file = subprocess.run([fnetctl, "--host", SERVER_IP, "--port", str(API_PORT), "--tls-ca", cert,
                                "--token-file", token_file, "status"], env=env, capture_output=True, text=True, timeout=60)
    assert with_file.returncode == 0, with_file.stderr
    with_env = subprocess.run([fnetctl, "--host", SERVER_IP, "--port", str(API_PORT), "--tls-ca", cert, "status"],
                              env=dict(env, FNET_TOKEN=TOKEN), capture_output=True, text=True, timeout=60)
    assert with_env.returncode == 0, with_env.stderr
    print("ok: fnetctl is refused without the token, served with --token-file and with FNET_TOKEN")

    # The Python client.
    try:
        fnet.Client(SERVER_IP, API_PORT, tls=tls).runs()
        raise AssertionError("the Python client was served without the token")
    except fnet.RpcError as e:
        assert e.code == fnet.rpc.UNAUTHORIZED, e
    assert fnet.Client(SERVER_IP, API_PORT, token=TOKEN, tls=tls).runs() == []
    os.environ["FNET_TOKEN"] = TOKEN
    assert fnet.Client(SERVER_IP, API_PORT, tls=tls).status()["ingest"] == "running"
    del os.environ["FNET_TOKEN"]
    print("ok: the Python client is refused without the token, served with token= and FNET_TOKEN")

    # The dashboard: 401 without the token; the page opened once with ?token= sets the cookie.
    base = f"https://{SERVER_IP}:{HTTP_PORT}"
    no_redirect = urllib.request.build_opener(NoRedirect, urllib.request.HTTPSHandler(context=tls))
    for path in ("/", "/rpc", "/index.html"):
        try:
            no_redirect.open(base + path, timeout=10)
            raise AssertionError(f"{path} was served without the token")
        except urllib.error.HTTPError as e:
            assert e.code == 401, (path, e.code)
    try:
        no_redirect.open(base + "/?token=" + TOKEN, timeout=10)
        raise AssertionError("no redirect")
    except urllib.error.HTTPError as e:
        assert e.code == 303, e.code
        assert e.headers["Location"] == "/", e.headers["Location"]
        cookie = e.headers["Set-Cookie"].split(";")[0]
        assert "Secure" in e.headers["Set-Cookie"], e.headers["Set-Cookie"]
    assert cookie == f"fnet_token_{HTTP_PORT}={TOKEN}", cookie
    page = urllib.request.urlopen(urllib.request.Request(base + "/", headers={"Cookie": cookie}), timeout=10,
                                  context=tls)
    assert page.status == 200 and b"<html" in page.read()
    try:
        WebSocket(SERVER_IP, HTTP_PORT, cookie=None, tls=tls)
        raise AssertionError("the WebSocket opened without the token")
    except HandshakeRefused as e:
        assert e.status == 401, e
    ws = WebSocket(SERVER_IP, HTTP_PORT, cookie=cookie, origin=base, tls=tls)
    answer = ws.call("runs.list")
    assert answer["result"] == {"runs": []}, answer
    ws.close()
    print("ok: the dashboard answers 401 without the token; ?token= once, then its cookie, opens the page and "
          "the WebSocket")


class NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args, **kwargs):
        return None


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "client":
        client_checks(sys.argv[2], sys.argv[3], sys.argv[4])
        return 0
    source_dir, build_dir, work = (os.path.abspath(a) for a in sys.argv[1:4])
    server = os.path.join(build_dir, "bin", "fnet-server")
    tag = f"fa{os.getpid()}"
    srv, cli = tag + "s", tag + "c"
    if subprocess.run(["ip", "netns", "add", srv], capture_output=True).returncode != 0:
        print("cannot create network namespaces: skipped")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    process = None
    try:
        sh = lambda *a: subprocess.run(list(a), check=True)
        sh("ip", "netns", "add", cli)
        sh("ip", "link", "add", f"v{tag}", "type", "veth", "peer", "name", f"p{tag}")
        sh("ip", "link", "set", f"v{tag}", "netns", srv)
        sh("ip", "link", "set", f"p{tag}", "netns", cli)
        sh("ip", "-n", srv, "addr", "add", f"{SERVER_IP}/24", "dev", f"v{tag}")
        sh("ip", "-n", cli, "addr", "add", f"{CLIENT_IP}/24", "dev", f"p{tag}")
        for ns, dev in ((srv, f"v{tag}"), (cli, f"p{tag}")):
            sh("ip", "-n", ns, "link", "set", "lo", "up")
            sh("ip", "-n", ns, "link", "set", dev, "up")
        env = dict(os.environ, CYCLONEDDS_URI=f"file://{source_dir}/deploy/cyclonedds-loopback.xml")
        on_server = ["ip", "netns", "exec", srv]
        flags = ["--data-dir", os.path.join(work, "data"), "--bind", SERVER_IP, "--port", str(API_PORT),
                 "--http-port", str(HTTP_PORT), "--domain", str(DOMAIN), "--threads", "1"]

        # No TLS: refused at start, naming what is missing.
        refused = subprocess.run(on_server + [server] + flags, env=env, capture_output=True, text=True, timeout=60)
        assert refused.returncode == 2, (refused.returncode, refused.stderr)
        assert "--tls-cert" in refused.stderr and SERVER_IP in refused.stderr, refused.stderr
        print(f"ok: fnet-server refuses --bind {SERVER_IP} without TLS: {refused.stderr.strip()}")
        sh("openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-days",
           "1", "-subj", f"/CN={SERVER_IP}", "-addext", f"subjectAltName=IP:{SERVER_IP}", "-keyout",
           os.path.join(work, "key.pem"), "-out", os.path.join(work, "cert.pem"))
        flags += ["--tls-cert", os.path.join(work, "cert.pem"), "--tls-key", os.path.join(work, "key.pem")]
        token_file = os.path.join(work, "token")
        with open(token_file, "w") as f:
            f.write(TOKEN + "\n")
        os.chmod(token_file, 0o600)

        out = open(os.path.join(work, "server.out"), "w")
        err = open(os.path.join(work, "server.err"), "w")
        process = subprocess.Popen(on_server + [server] + flags + ["--token-file", token_file], env=env, stdout=out,
                                   stderr=err)
        deadline = time.monotonic() + 30
        while "dashboard on" not in open(os.path.join(work, "server.out")).read():
            assert process.poll() is None, open(os.path.join(work, "server.err")).read()
            assert time.monotonic() < deadline, "fnet-server did not start"
            time.sleep(0.1)
        print("fnet-server in namespace", srv, "on", SERVER_IP, ":", open(os.path.join(work, "server.out")).read())
        subprocess.run(["ip", "netns", "exec", cli, sys.executable, os.path.abspath(__file__), "client", source_dir,
                        build_dir, token_file], check=True, timeout=300)
        return 0
    finally:
        if process:
            process.terminate()
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                process.kill()
        for ns in (srv, cli):
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)


if __name__ == "__main__":
    sys.exit(main())
