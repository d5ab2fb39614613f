// One WebSocket to the editor server: calls {id, method, params} answered by
// {id, result | error}, and events {event, ...} sent to every view.
export class Connection {
  constructor(url) {
    this.url = url;
    this.next = 1;
    this.pending = new Map();
    this.handlers = new Map();
  }
  open() {
    return new Promise((resolve, reject) => {
      this.ws = new WebSocket(this.url);
      this.ws.onopen = () => resolve();
      this.ws.onerror = () => reject(new Error('cannot reach the editor server'));
      this.ws.onclose = () => this.emit('closed', {});
      this.ws.onmessage = (m) => {
        let msg;
        try { msg = JSON.parse(m.data); } catch { return; }
        if (msg.event) return this.emit(msg.event, msg);
        const p = this.pending.get(msg.id);
        if (!p) return;
        this.pending.delete(msg.id);
        if (msg.error) p.reject(new Error(msg.error.message));
        else p.resolve(msg.result);
      };
    });
  }
  call(method, params) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.ws.send(JSON.stringify({ id, method, params }));
    });
  }
  on(event, f) { this.handlers.set(event, f); }
  emit(event, msg) { const f = this.handlers.get(event); if (f) f(msg); }
}
