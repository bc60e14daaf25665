// The link tree of a URDF text, read with the browser's XML parser for the URDF picker
// (web/urdf_upload.js) alone: enough to offer root and tip choices for a user's file
// before it is loaded. Once loaded, the page reads the robot from the module
// (robot.links, robot.joints): achd's loader (urdfdom) is the parser.

export function urdfTree(text) {
  const doc = new DOMParser().parseFromString(text, 'application/xml');
  const robot = doc.documentElement;
  if (doc.querySelector('parsererror') || robot.nodeName !== 'robot') {
    throw new Error('not a URDF file: expected an XML document whose root element is <robot>');
  }
  const links = [...robot.children].filter((e) => e.nodeName === 'link').map((e) => e.getAttribute('name'));
  // child link -> {parent link, joint type}
  const parentOf = new Map();
  for (const e of robot.children) {
    if (e.nodeName !== 'joint') continue;
    const parent = e.querySelector('parent')?.getAttribute('link');
    const child = e.querySelector('child')?.getAttribute('link');
    if (parent && child) parentOf.set(child, { parent, type: e.getAttribute('type') });
  }
  return { links, parentOf };
}

// Links from root to tip (root first), or null when tip does not descend from root.
export function chainLinks(tree, root, tip) {
  const chain = [tip];
  for (let link = tip; link !== root; ) {
    const up = tree.parentOf.get(link);
    if (!up || chain.length > tree.links.length) return null;
    link = up.parent;
    chain.push(link);
  }
  return chain.reverse();
}

export function isMovable(tree, link) {
  const type = tree.parentOf.get(link)?.type;
  return Boolean(type) && type !== 'fixed';
}

// Suggested chain for a file the user drops: from the tree's root to its deepest leaf.
export function longestChain(tree) {
  const root = tree.links.find((l) => !tree.parentOf.has(l)) ?? tree.links[0];
  let best = { tip: root, length: 0 };
  for (const link of tree.links) {
    const chain = chainLinks(tree, root, link);
    if (chain && chain.length > best.length) best = { tip: link, length: chain.length };
  }
  return { root, tip: best.tip };
}
