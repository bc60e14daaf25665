// Own URDFs in the page's link. A URDF whose compressed text is short enough travels in
// the link itself: urdf=deflate:<base64url of its deflate-raw bytes> (CompressionStream),
// which opens it in any browser. A longer one is kept in this browser's localStorage under
// its hash, and the link names it: urdf=local:<first 16 hex digits of its SHA-256>, which
// reopens it in this browser only. Its mesh files are never in the link: they are kept in
// this browser's IndexedDB under the same key (web/mesh_share.js). The SRDF an own URDF
// was loaded with goes the same way (srdf=deflate:… or srdf=local:…), cut to its
// group_states, the only part achd reads (web/srdf_poses.js).

import { inflatedSize } from './deflate_size.js';

// Longest compressed URDF, in base64url characters, that a link carries: links of a few
// kilobytes pass through mail and chat programs intact.
export const LINK_CHARACTERS = 8000;
// Largest URDF text a link may carry once decompressed: the command line's limit on a URDF
// file (64 MiB). A link of a few hundred KB can expand to gigabytes; decompression stops
// as soon as the text passes this, instead of filling the tab's memory.
export const URDF_LIMIT_BYTES = 64 * 1024 * 1024;
// Where localStorage keeps a text of each kind the link names.
const STORAGE_PREFIX = { URDF: 'achd:urdf:', SRDF: 'achd:srdf:' };
const CARRIED = 'deflate:';
const KEPT = 'local:';

// The key a URDF is kept under: the first 16 hex digits of the SHA-256 of its text.
export async function urdfKey(text) {
  const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', new TextEncoder().encode(text)));
  return Array.from(digest.subarray(0, 8), (b) => b.toString(16).padStart(2, '0')).join('');
}

// {ref: the hash's urdf= value, form: 'link' | 'local', characters: length of the
// compressed text in base64url, key: urdfKey(text)}. Throws when the URDF is too long for
// a link and the browser's storage refuses it.
export async function shareUrdf(text) {
  return shareText(text, 'URDF');
}

// The same for an SRDF's text (kept under the SHA-256 of the text given).
export async function shareSrdf(text) {
  return shareText(text, 'SRDF');
}

// The text a srdf= value names; throws an Error saying why it cannot be had.
export async function openSharedSrdf(ref) {
  return openShared(ref, 'SRDF');
}

async function shareText(text, kind) {
  const packed = toBase64url(await transform(new TextEncoder().encode(text), new CompressionStream('deflate-raw')));
  const key = await urdfKey(text);
  if (packed.length <= LINK_CHARACTERS) return { ref: CARRIED + packed, form: 'link', characters: packed.length, key };
  try {
    localStorage.setItem(STORAGE_PREFIX[kind] + key, text);
  } catch (err) {
    throw new Error(`it is too long for a link (${packed.length} characters compressed, at most ${LINK_CHARACTERS}) ` +
      `and this browser's storage refused it (${err.name}): it cannot be shared by link`);
  }
  return { ref: KEPT + key, form: 'local', characters: packed.length, key };
}

// The URDF text a urdf= value names; throws an Error saying why it cannot be had.
export async function openSharedUrdf(ref) {
  return openShared(ref, 'URDF');
}

async function openShared(ref, kind) {
  if (ref.startsWith(CARRIED)) {
    let bytes;
    try {
      const packed = fromBase64url(ref.slice(CARRIED.length));
      // Measured first without expanding (milliseconds, web/deflate_size.js); a stream the
      // count cannot read is left to the decompressor, which says what is wrong with it.
      let size = 0;
      try {
        size = inflatedSize(packed, URDF_LIMIT_BYTES);
      } catch {
        size = 0;
      }
      if (size > URDF_LIMIT_BYTES) throw new TooLarge(tooLargeMessage(URDF_LIMIT_BYTES, kind));
      bytes = await inflateBounded(packed, URDF_LIMIT_BYTES, kind);
    } catch (err) {
      if (err instanceof TooLarge) throw new Error(err.message);
      throw new Error(`the ${kind} carried in the link is damaged (${err.message}); was the link cut short?`);
    }
    return new TextDecoder().decode(bytes);
  }
  if (ref.startsWith(KEPT)) {
    const key = ref.slice(KEPT.length);
    const text = localStorage.getItem(STORAGE_PREFIX[kind] + key);
    if (text === null) {
      throw new Error(`the own ${kind} of this link (${ref}) is not in this browser's storage: such a link reopens ` +
        `a ${kind} only in the browser that loaded it; load the file here`);
    }
    return text;
  }
  throw new Error(`${kind.toLowerCase()}= must start with ${CARRIED} or ${KEPT}, got "${ref.slice(0, 20)}"`);
}

class TooLarge extends Error {}

function tooLargeMessage(limit, kind) {
  return `the ${kind} carried in the link expands past the ${limit / (1024 * 1024)} MiB limit of a URDF file; ` +
    'it was not opened';
}

// The deflate-raw `bytes` decompressed, read chunk by chunk: past `limit` bytes the stream
// is cancelled (which stops the decompressor) and TooLarge says so, the chunks read so far
// left to the garbage collector. (inflatedSize has refused such a link before; this bound
// holds whatever the count made of the stream.)
async function inflateBounded(bytes, limit, kind) {
  const reader = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const chunks = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > limit) {
      chunks.length = 0;
      await reader.cancel().catch(() => {});
      throw new TooLarge(tooLargeMessage(limit, kind));
    }
    chunks.push(value);
  }
  const out = new Uint8Array(total);
  let at = 0;
  for (const chunk of chunks) {
    out.set(chunk, at);
    at += chunk.length;
  }
  return out;
}

async function transform(bytes, stream) {
  const out = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}

function toBase64url(bytes) {
  let binary = '';
  const CHUNK = 0x8000;
  for (let i = 0; i < bytes.length; i += CHUNK) binary += String.fromCharCode(...bytes.subarray(i, i + CHUNK));
  return btoa(binary).replaceAll('+', '-').replaceAll('/', '_').replace(/=+$/, '');
}

function fromBase64url(text) {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new Error('characters other than base64url');
  const binary = atob(text.replaceAll('-', '+').replaceAll('_', '/'));
  return Uint8Array.from(binary, (c) => c.charCodeAt(0));
}
