"""A small WebSocket client (RFC 6455) for the tests: the dashboard's JSON-RPC at /rpc, from Python
without a package beyond the standard library. Text messages only; pings answered; no extensions."""

import base64
import json
import os
import socket
import struct


class HandshakeRefused(Exception):
    """The server answered the upgrade with another status: `status` and `body`."""

    def __init__(self, status, body):
        super().__init__(f"upgrade refused: {status} {body!r}")
        self.status = status
        self.body = body


class WebSocket:
    def __init__(self, host, port, path="/rpc", cookie=None, origin=None, timeout=30.0, tls=None):
        """`tls`: an ssl.SSLContext to speak wss (the host name checked against the certificate)."""
        self.sock = socket.create_connection((host, port), timeout=timeout)
        if tls is not None:
            self.sock = tls.wrap_socket(self.sock, server_hostname=host)
        key = base64.b64encode(os.urandom(16)).decode()
        lines = [f"GET {path} HTTP/1.1", f"Host: {host}:{port}", "Upgrade: websocket", "Connection: Upgrade",
                 f"Sec-WebSocket-Key: {key}", "Sec-WebSocket-Version: 13"]
        if cookie:
            lines.append(f"Cookie: {cookie}")
        if origin:
            lines.append(f"Origin: {origin}")
        self.sock.sendall(("\r\n".join(lines) + "\r\n\r\n").encode())
        self._buffer = b""
        head = self._read_until(b"\r\n\r\n").decode(errors="replace")
        status = int(head.split(" ", 2)[1])
        if status != 101:
            length = next((int(h.split(":", 1)[1]) for h in head.split("\r\n") if h.lower().startswith("content-length:")),
                          0)
            raise HandshakeRefused(status, self._read_exactly(length).decode(errors="replace"))
        self._next_id = 1

    def _read_until(self, marker):
        while marker not in self._buffer:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("closed during the handshake")
            self._buffer += chunk
        head, self._buffer = self._buffer.split(marker, 1)
        return head

    def _read_exactly(self, n):
        while len(self._buffer) < n:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("the connection closed")
            self._buffer += chunk
        out, self._buffer = self._buffer[:n], self._buffer[n:]
        return out

    def _send_frame(self, opcode, payload):
        mask = os.urandom(4)
        n = len(payload)
        head = bytes([0x80 | opcode])
        if n < 126:
            head += bytes([0x80 | n])
        elif n < 65536:
            head += bytes([0x80 | 126]) + struct.pack(">H", n)
        else:
            head += bytes([0x80 | 127]) + struct.pack(">Q", n)
        masked = bytes(b ^ mask[k % 4] for k, b in enumerate(payload))
        self.sock.sendall(head + mask + masked)

    def send_text(self, text):
        self._send_frame(0x1, text.encode())

    def receive(self):
        """The next text message; ConnectionError with the close code when the server closed."""
        message = b""
        while True:
            b0, b1 = self._read_exactly(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read_exactly(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read_exactly(8))[0]
            payload = self._read_exactly(n)
            opcode = b0 & 0x0F
            if opcode == 0x8:
                code = struct.unpack(">H", payload[:2])[0] if len(payload) >= 2 else None
                raise ConnectionError(f"closed by the server (code {code})")
            if opcode == 0x9:
                self._send_frame(0xA, payload)
                continue
            message += payload
            if b0 & 0x80:
                return message.decode()

    def call(self, method, params=None):
        """One JSON-RPC call; its response (notifications before it are skipped)."""
        request_id = self._next_id
        self._next_id += 1
        request = {"jsonrpc": "2.0", "id": request_id, "method": method}
        if params is not None:
            request["params"] = params
        self.send_text(json.dumps(request))
        while True:
            message = json.loads(self.receive())
            if message.get("id") == request_id:
                return message

    def close(self):
        self.sock.close()
