// three.js objects for a URDF's visuals (robot.links, web/link_visuals.js): boxes,
// cylinders and spheres at once, meshes once their file is read and parsed by the loaders
// that ship with three (STL, COLLADA, OBJ). Each object sits at its visual's origin in
// the link frame: p_link = T(position) R(rotation) S(scale) p_mesh.
import * as THREE from 'three';

// Imported when a mesh of that format is first read: a robot of solids starts without them.
const LOADERS = {
  stl: async () => (await import('three/addons/loaders/STLLoader.js')).STLLoader,
  dae: async () => (await import('three/addons/loaders/ColladaLoader.js')).ColladaLoader,
  obj: async () => (await import('three/addons/loaders/OBJLoader.js')).OBJLoader,
};

// Farthest a mesh's vertex may lie from its visual's origin once scaled, in metres: a
// robot's part spans centimetres to metres; a vertex kilometres away (or NaN, or
// infinite) is a broken file, and drawing it would throw the camera's framing off (to NaN
// matrices). Such a mesh is refused: its link keeps the stick figure and the note says why.
export const MAX_VERTEX_METRES = 1000;

const DEFAULT_COLOR = [0.72, 0.75, 0.79, 1];
// What a texture that was not found is drawn with: one white pixel (PNG), so the mesh
// keeps its material colour and the browser fetches nothing.
const BLANK_TEXTURE = 'data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC';

// A pose {position: [3], rotation: [9, row-major]} (achd's placements) as a THREE.Matrix4.
export function placementMatrix(p, out = new THREE.Matrix4()) {
  const r = p.rotation;
  const x = p.position;
  return out.set(r[0], r[1], r[2], x[0], r[3], r[4], r[5], x[1], r[6], r[7], r[8], x[2], 0, 0, 0, 1);
}

// -> {object: THREE.Group at the visual's origin, load: null for a primitive, or
//     async (files) => {filename, status: 'loaded' | 'missing' | 'failed', message,
//                       texturesMissing: the textures the mesh names that were not found}}
// files: PickedFiles or ServedFiles (web/mesh_files.js); without files (a URDF given as
// text alone) every mesh is missing.
export function visualObject(visual) {
  const object = new THREE.Group();
  placementMatrix(visual).decompose(object.position, object.quaternion, new THREE.Vector3());
  const g = visual.geometry;
  if (g.type !== 'mesh') {
    object.add(new THREE.Mesh(primitiveGeometry(g), material(visual.color)));
    return { object, load: null };
  }
  object.scale.fromArray(g.scale);
  const load = async (files) => {
    const result = { filename: g.filename, status: 'loaded', message: '', texturesMissing: [] };
    const format = Object.keys(LOADERS).find((f) => g.filename.toLowerCase().endsWith(`.${f}`));
    if (!format) return { ...result, status: 'failed', message: 'not STL, DAE or OBJ' };
    let bytes;
    try {
      bytes = files ? await files.read(g.filename) : null;
    } catch (err) {
      return { ...result, status: 'failed', message: err.message };
    }
    if (!bytes) return { ...result, status: 'missing' };
    const Loader = await LOADERS[format]();
    // Textures (COLLADA images) come from the same files as the mesh.
    const manager = new THREE.LoadingManager();
    manager.setURLModifier((url) => {
      if (/^(data|blob):/.test(url)) return url;
      const found = files.textureUrl(g.filename, url);
      if (found) return found;
      result.texturesMissing.push(url);
      return BLANK_TEXTURE;
    });
    let mesh;
    try {
      mesh = parseMesh(new Loader(manager), format, bytes, visual.color);
    } catch (err) {
      return { ...result, status: 'failed', message: `not a readable ${format.toUpperCase()} file (${err.message})` };
    }
    const bad = badVertex(mesh, g.scale);
    if (bad) {
      dispose(mesh);
      return { ...result, status: 'failed', message: bad };
    }
    object.add(mesh);
    return result;
  };
  return { object, load };
}

// Why the vertices of a parsed mesh cannot be drawn, or null when they can: the first
// one that is not finite, or one farther than MAX_VERTEX_METRES from the visual's origin
// once the mesh's own transforms (a COLLADA unit) and the URDF's scale apply.
function badVertex(mesh, scale) {
  let why = null;
  mesh.traverse((o) => {
    const position = o.isMesh ? o.geometry.getAttribute('position') : null;
    if (why || !position) return;
    const a = position.array;
    for (let i = 0; i < a.length; i++) {
      if (!Number.isFinite(a[i])) {
        why = `vertex ${Math.floor(i / 3) + 1} has a coordinate that is not a finite number (${a[i]})`;
        return;
      }
    }
  });
  if (why) return why;
  mesh.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(mesh);
  const factor = Math.max(...scale.map(Math.abs));
  const far = factor * Math.max(...[box.min, box.max].flatMap((v) => [Math.abs(v.x), Math.abs(v.y), Math.abs(v.z)]));
  if (!(far <= MAX_VERTEX_METRES)) {
    return `a vertex lies ${far.toPrecision(3)} m from the visual's origin, more than the ${MAX_VERTEX_METRES} m ` +
      'a robot\'s mesh may span';
  }
  return null;
}

function dispose(object) {
  object.traverse((o) => {
    o.geometry?.dispose();
    for (const m of [o.material ?? []].flat()) m.dispose();
  });
}

function primitiveGeometry(g) {
  switch (g.type) {
    case 'box':
      return new THREE.BoxGeometry(...g.size);
    case 'sphere':
      return new THREE.SphereGeometry(g.radius, 24, 16);
    case 'cylinder':
      // URDF's cylinder is along z, three's along y.
      return new THREE.CylinderGeometry(g.radius, g.radius, g.length, 28).rotateX(Math.PI / 2);
    default:
      throw new Error(`no primitive ${g.type}`);
  }
}

function material(color) {
  const [r, g, b, a] = color ?? DEFAULT_COLOR;
  return new THREE.MeshStandardMaterial({
    color: new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace),
    roughness: 0.55,
    metalness: 0.1,
    transparent: a < 1,
    opacity: a,
  });
}

// A mesh file's contents as an Object3D in its own coordinates. A URDF color replaces the
// file's materials; without one an STL or OBJ gets the default grey, a COLLADA file keeps
// its own. COLLADA's up axis is not applied (URDF tools read a mesh's vertices in the link
// frame), its unit is.
function parseMesh(loader, format, bytes, color) {
  if (format === 'stl') {
    const geometry = loader.parse(bytes);
    if (!geometry.getAttribute('position')?.count) throw new Error('no triangles');
    return new THREE.Mesh(geometry, material(color));
  }
  const text = new TextDecoder().decode(bytes);
  let object;
  if (format === 'dae') {
    const collada = loader.parse(text, '');
    if (!collada) throw new Error('no COLLADA document');
    object = collada.scene;
    object.rotation.set(0, 0, 0);
  } else {
    object = loader.parse(text);
  }
  let triangles = 0;
  object.traverse((o) => {
    if (!o.isMesh) return;
    triangles += o.geometry.getAttribute('position')?.count ?? 0;
    if (color || format === 'obj') o.material = material(color);
  });
  if (!triangles) throw new Error('no triangles');
  return object;
}
