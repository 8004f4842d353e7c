"""deploy/demo.sh prints the dashboard's address while its run goes on, and the page and the run's
series are served there meanwhile (DDS domain 48, ports picked free).

usage: demo_dashboard_test.py SOURCE_DIR BUILD_DIR WORK_DIR
"""

import os
import shutil
import subprocess
import sys
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dashboard_fixture import free_port  # noqa: E402
from websocket_client import WebSocket  # noqa: E402


def main():
    source_dir, build_dir, work = (os.path.abspath(a) for a in sys.argv[1:4])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    port, http_port = free_port(), free_port()
    env = dict(os.environ, PORT=str(port), HTTP_PORT=str(http_port), DOMAIN_ID="48", BIN_DIR=build_dir,
               DATA_DIR=os.path.join(work, "data"), PARTICLES="100", FRAMES="12", SPEED="1e-3")
    demo = subprocess.Popen(["bash", os.path.join(source_dir, "deploy", "demo.sh")], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, cwd=source_dir)
    out = []
    try:
        for line in demo.stdout:
            out.append(line)
            if line.startswith("dashboard: "):
                break
        else:
            raise AssertionError("demo.sh printed no dashboard address:\n" + "".join(out))
        url = f"http://127.0.0.1:{http_port}/"
        assert line.startswith(f"dashboard: {url} "), line
        page = urllib.request.urlopen(url, timeout=10)
        assert page.status == 200 and b"<title>fnet" in page.read()
        ws = WebSocket("127.0.0.1", http_port, origin=url.rstrip("/"))
        status = ws.call("server.status")["result"]
        assert status["ingest"] == "running", status
        ws.close()
        print(f"ok: demo.sh printed {line.strip()!r} and the page is served there while the demo runs")
        out.extend(demo.stdout)
        assert demo.wait(600) == 0, "".join(out)
        print("ok: the demo ended normally")
        return 0
    finally:
        if demo.poll() is None:
            demo.terminate()
            demo.wait(30)


if __name__ == "__main__":
    sys.exit(main())
