// The base of every object that owns wasm memory.
import { achdWasm } from './runtime.mjs';

// The part every wasm-owning object shares: a pointer, delete(), and Float64Array views
// re-created whenever the wasm memory buffer has been replaced (by growth, or by a
// delete() that detached the views).
//
// Views cannot outlive their object: a view is a Float64Array on wasm memory, which JS
// cannot take back, so delete() of an object whose views were handed out on the current
// memory buffer frees the object and then replaces the buffer (achdWasm.detachViews):
// every view made before, of this object or any other, becomes zero-length, and a write
// through it is dropped instead of landing in memory the allocator or a new object owns.
// The getters make a live object's views again on the new buffer.
export class AchdHandle {
  constructor(kind, ptr, free) {
    this._kind = kind;
    this._ptr = ptr;
    this._free = free;
    this._buffer = null;
    this._views = null;
    this._viewsHandedOn = null;  // the memory buffer of the last view given to the caller
  }
  _live() {
    if (this._ptr === 0) throw new Error(`${this._kind} has been deleted`);
    return this._ptr;
  }
  // _layout(): [name, length] per view; _bufferNames(): the C++ buffer names (index =
  // the buffer's number in achd_*_buffer); _bufferOf(ptr, index): its byte address.
  // _view: a view for the caller (remembered, see delete()); _ownView: one the wrapper
  // reads itself and does not hand out.
  _view(name) {
    const view = this._ownView(name);
    this._viewsHandedOn = view.buffer;
    return view;
  }
  _ownView(name) {
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
    const ptr = this._live();
    this._ptr = 0;
    this._views = null;
    this._buffer = null;
    this._free(ptr);
    // Views given out on the current buffer may still be held: detach them all.
    if (this._viewsHandedOn !== null && this._viewsHandedOn === achdWasm.module.HEAPF64.buffer) achdWasm.detachViews();
    this._viewsHandedOn = null;
  }
}
