// The files a URDF's meshes are looked up in: the files the user picked or dropped
// together with the URDF (a folder, or several files), or, for a robot of robots/, the
// server's files next to its URDF. A mesh filename is
//   package://PKG/path  (a ROS package: PKG is usually the folder the URDF's package is in),
//   file:///abs/path, or a path relative to the URDF's folder.
// Among the user's files, the one whose path shares the longest tail of folder names
// with the filename wins (its file name at least must match): a folder picked at any
// level, or loose files, then still resolve. A mesh's textures are looked up the same
// way, relative to the mesh's folder. The files a robot's looks were read from are what a
// share link keeps of them (web/mesh_share.js).

// Largest mesh file read, in bytes: a robot's meshes are kilobytes to a few megabytes; a
// larger file is refused (its link keeps the stick figure) rather than read whole.
export const MESH_LIMIT_BYTES = 64 * 1024 * 1024;

function tooLarge(bytes) {
  return new Error(`${bytes} bytes, larger than the ${MESH_LIMIT_BYTES / (1024 * 1024)} MiB limit of a mesh file`);
}

// files: [{path: 'robot/meshes/a.stl' (folder-relative, '/'-separated), file: File}];
// urdfPath: the URDF's own path among them.
export class PickedFiles {
  constructor(files, urdfPath) {
    this.files = files.map(({ path, file }) => ({ parts: splitPath(path), file }));
    this.urdfPath = urdfPath;
    this.urdfFolder = splitPath(urdfPath).slice(0, -1);
    this.objectUrls = new Map();
    // The files read so far, meshes and textures.
    this.used = new Set();
  }

  // [{path, file}] of the files read so far, in the order given: among them alone, every
  // filename read resolves to the same file again.
  usedFiles() {
    return this.files.filter((f) => this.used.has(f)).map((f) => ({ path: f.parts.join('/'), file: f.file }));
  }

  // The picked file {parts, file} at the path parts `wanted`, or the one sharing the
  // longest tail with them; null when no file name matches.
  match(wanted) {
    if (!wanted.length) return null;
    const exact = this.files.find((f) => samePath(f.parts, wanted));
    if (exact) return exact;
    let best = null;
    let bestShared = 0;
    for (const f of this.files) {
      const shared = sharedTail(f.parts, wanted);
      if (shared > bestShared) {
        best = f;
        bestShared = shared;
      }
    }
    return best;
  }

  // The mesh's bytes, or null when no picked file matches.
  async read(filename) {
    const hit = this.match(meshParts(filename, this.urdfFolder));
    if (!hit) return null;
    if (hit.file.size > MESH_LIMIT_BYTES) throw tooLarge(hit.file.size);
    this.used.add(hit);
    return hit.file.arrayBuffer();
  }

  // A URL the browser can load a mesh's texture from (a blob: URL of the picked file),
  // or null. ref: the texture's path as the mesh file gives it.
  textureUrl(meshFilename, ref) {
    const mesh = this.match(meshParts(meshFilename, this.urdfFolder));
    const folder = mesh ? mesh.parts.slice(0, -1) : this.urdfFolder;
    const hit = this.match(normalize([...folder, ...splitPath(ref.replace(/^file:\/\//i, ''))]));
    if (!hit) return null;
    this.used.add(hit);
    if (!this.objectUrls.has(hit.file)) this.objectUrls.set(hit.file, URL.createObjectURL(hit.file));
    return this.objectUrls.get(hit.file);
  }
}

// Meshes of a robot the page serves (robots/...): relative to the URDF's URL.
export class ServedFiles {
  constructor(urdfUrl) {
    this.urdfUrl = urdfUrl;
  }

  async read(filename) {
    if (/^[a-z]+:\/\//i.test(filename)) return null;  // package:// or file://: not on this server
    const response = await fetch(new URL(filename, this.urdfUrl));
    if (!response.ok) return null;
    const bytes = await response.arrayBuffer();
    if (bytes.byteLength > MESH_LIMIT_BYTES) throw tooLarge(bytes.byteLength);
    return bytes;
  }

  // A texture next to the mesh on this server.
  textureUrl(meshFilename, ref) {
    return new URL(ref, new URL(meshFilename, this.urdfUrl)).href;
  }
}

// The path parts a mesh filename points at, relative to the folder the files were
// picked from when it can be told (a relative path), or just its tail otherwise.
function meshParts(filename, urdfFolder) {
  const pkg = /^package:\/\/(.*)$/i.exec(filename);
  if (pkg) return splitPath(pkg[1]);
  const file = /^file:\/\/(.*)$/i.exec(filename);
  if (file) return splitPath(file[1]);
  return normalize([...urdfFolder, ...splitPath(filename)]);
}

function splitPath(path) {
  return String(path).split(/[\\/]+/).filter((p) => p && p !== '.');
}

// Resolves '..' parts (a path above the picked folder keeps only what stays inside).
function normalize(parts) {
  const out = [];
  for (const p of parts) {
    if (p === '..') out.pop();
    else out.push(p);
  }
  return out;
}

function samePath(a, b) {
  return a.length === b.length && a.every((p, i) => p === b[i]);
}

// How many trailing path parts a and b share.
function sharedTail(a, b) {
  let n = 0;
  while (n < a.length && n < b.length && a[a.length - 1 - n] === b[b.length - 1 - n]) n++;
  return n;
}

// Every file of a drop, folders read recursively: [{path, file}].
export async function droppedFiles(dataTransfer) {
  const entries = [...dataTransfer.items]
    .filter((item) => item.kind === 'file')
    .map((item) => item.webkitGetAsEntry?.())
    .filter(Boolean);
  if (!entries.length) return [...dataTransfer.files].map((file) => ({ path: file.name, file }));
  const out = [];
  await Promise.all(entries.map((entry) => readEntry(entry, '', out)));
  return out;
}

async function readEntry(entry, prefix, out) {
  const path = prefix + entry.name;
  if (entry.isFile) {
    const file = await new Promise((resolve, reject) => entry.file(resolve, reject));
    out.push({ path, file });
    return;
  }
  const reader = entry.createReader();
  // readEntries hands out a folder's entries in batches until an empty one.
  for (;;) {
    const batch = await new Promise((resolve, reject) => reader.readEntries(resolve, reject));
    if (!batch.length) break;
    await Promise.all(batch.map((child) => readEntry(child, `${path}/`, out)));
  }
}

// Files from an <input type="file"> (a folder picker gives webkitRelativePath).
export function pickedFiles(fileList) {
  return [...fileList].map((file) => ({ path: file.webkitRelativePath || file.name, file }));
}
