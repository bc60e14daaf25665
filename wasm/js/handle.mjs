// The base of every object that owns wasm memory.
import { achdWasm } from './runtime.mjs';

// The part every wasm-owning object shares: a pointer, delete(), and Float64Array views
// re-created whenever the wasm memory buffer has been replaced by growth.
export class AchdHandle {
  constructor(kind, ptr, free) {
    this._kind = kind;
    this._ptr = ptr;
    this._free = free;
    this._buffer = null;
    this._views = null;
  }
  _live() {
    if (this._ptr === 0) throw new Error(`${this._kind} has been deleted`);
    return this._ptr;
  }
  // _layout(): [name, length] per view; _bufferNames(): the C++ buffer names (index =
  // the buffer's number in achd_*_buffer); _bufferOf(ptr, index): its byte address.
  _view(name) {
    if (this._ptr === 0) throw new Error(`${this._kind} has been deleted`);
    if (this._buffer !== achdWasm.module.HEAPF64.buffer) this._mapViews();
    return this._views[name];
  }
  _mapViews() {
    this._buffer = achdWasm.module.HEAPF64.buffer;
    this._views = {};
    const names = this._bufferNames();
    for (const v of this._layout())  // v = [name, length]
      this._views[v[0]] = new Float64Array(this._buffer, this._bufferOf(this._ptr, names.indexOf(v[0])), v[1]);
  }
  get deleted() { return this._ptr === 0; }
  delete() {
    this._live();
    this._free(this._ptr);
    this._ptr = 0;
    this._views = null;
    this._buffer = null;
  }
}
