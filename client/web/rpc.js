// The JSON-RPC API of fnet-server over the dashboard's WebSocket (/rpc): calls answered by id,
// notifications handed to their listeners, and a reconnection (with a growing delay) when the
// connection drops; onOpen listeners run after each (re)connection, to subscribe again.

export class RpcError extends Error {
  constructor(error) {
    super(error.message);
    this.code = error.code;
    this.data = error.data;
  }
}

export class Rpc {
  constructor(url) {
    this.url = url;
    this.nextId = 1;
    this.pending = new Map();  // id -> {resolve, reject}
    this.listeners = new Map();  // notification method -> [fn]
    this.openListeners = [];
    this.stateListeners = [];
    this.delay = 500;
    this.open = false;
    this.connect();
  }

  connect() {
    const ws = new WebSocket(this.url);
    this.ws = ws;
    ws.onopen = () => {
      this.open = true;
      this.delay = 500;
      this.emitState("live");
      for (const fn of this.openListeners) fn();
    };
    ws.onmessage = (event) => this.receive(JSON.parse(event.data));
    ws.onclose = () => {
      const wasOpen = this.open;
      this.open = false;
      for (const { reject } of this.pending.values()) reject(new Error("connection to fnet-server lost"));
      this.pending.clear();
      this.emitState(wasOpen ? "lost" : "connecting");
      setTimeout(() => this.connect(), this.delay);
      this.delay = Math.min(this.delay * 2, 8000);
    };
  }

  receive(message) {
    if (Array.isArray(message)) return message.forEach((m) => this.receive(m));
    if (message.id !== undefined && message.id !== null) {
      const call = this.pending.get(message.id);
      if (!call) return;
      this.pending.delete(message.id);
      if (message.error) call.reject(new RpcError(message.error));
      else call.resolve(message.result);
      return;
    }
    if (message.error) return console.warn("fnet-server:", message.error.message);
    for (const fn of this.listeners.get(message.method) || []) fn(message.params);
  }

  call(method, params = {}) {
    if (!this.open) return Promise.reject(new Error("not connected to fnet-server"));
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.ws.send(JSON.stringify({ jsonrpc: "2.0", id, method, params }));
    });
  }

  on(method, fn) {
    if (!this.listeners.has(method)) this.listeners.set(method, []);
    this.listeners.get(method).push(fn);
  }

  onOpen(fn) {
    this.openListeners.push(fn);
    if (this.open) fn();
  }

  onState(fn) {
    this.stateListeners.push(fn);
  }

  emitState(state) {
    for (const fn of this.stateListeners) fn(state);
  }
}

// The WebSocket of the server that served this page.
export function dashboardSocketUrl() {
  return (location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/rpc";
}
