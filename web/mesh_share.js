// The mesh files of an own URDF, kept in this browser's IndexedDB for its share link: under
// the URDF's key (web/urdf_share.js's urdfKey, the first 16 hex digits of the SHA-256 of
// its text), the files its meshes and their textures were read from, with their paths and
// the URDF's path among them, so that they resolve as they did (web/mesh_files.js). A link
// names the URDF, and reopening it here finds its meshes by the same key; another browser
// has none. One record per URDF text: the files of its last load.
import { PickedFiles } from './mesh_files.js';

const DATABASE = 'achd';
const STORE = 'meshes';

function openDatabase() {
  return new Promise((resolve, reject) => {
    if (typeof indexedDB === 'undefined') {
      reject(new Error('this browser has no IndexedDB'));
      return;
    }
    const request = indexedDB.open(DATABASE, 1);
    request.onupgradeneeded = () => request.result.createObjectStore(STORE, { keyPath: 'key' });
    request.onsuccess = () => resolve(request.result);
    request.onerror = () => reject(storageError(request.error));
    request.onblocked = () => reject(new Error('IndexedDB is blocked by another page of this site'));
  });
}

// Runs fn(store) in one transaction; resolves with the value of the request fn returns,
// once the transaction has committed.
async function transact(mode, fn) {
  const db = await openDatabase();
  try {
    return await new Promise((resolve, reject) => {
      const tx = db.transaction(STORE, mode);
      const request = fn(tx.objectStore(STORE));
      tx.oncomplete = () => resolve(request.result);
      tx.onerror = () => reject(storageError(tx.error ?? request.error));
      tx.onabort = () => reject(storageError(tx.error ?? request.error));
    });
  } finally {
    db.close();
  }
}

function storageError(err) {
  return new Error(`IndexedDB: ${err?.name ?? 'Error'}${err?.message ? ` (${err.message})` : ''}`);
}

// Keeps the files a PickedFiles has read (web/mesh_files.js) under key; with none read,
// forgets what the key had. -> {files: how many were kept, bytes}. Throws an Error
// naming the storage's refusal (a full quota, a private window).
export async function keepMeshes(key, picked) {
  const files = picked.usedFiles();
  if (!files.length) {
    await transact('readwrite', (store) => store.delete(key));
    return { files: 0, bytes: 0 };
  }
  await transact('readwrite', (store) => store.put({ key, urdfPath: picked.urdfPath, files }));
  return { files: files.length, bytes: files.reduce((sum, f) => sum + f.file.size, 0) };
}

// The PickedFiles kept under key, or null when this browser keeps none for it.
export async function openKeptMeshes(key) {
  const record = await transact('readonly', (store) => store.get(key));
  return record ? new PickedFiles(record.files, record.urdfPath) : null;
}
