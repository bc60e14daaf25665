// The named poses of an SRDF file (its <group_state name="...">), read with the browser's
// XML parser so that the load form can offer them before the robot is loaded; achd reads
// the joint values (loadURDF's srdf and pose options, robot.poses).

// -> {robot: the <robot name>, poses: group_state names in file order}; throws on a file
// that is not an SRDF.
export function srdfPoses(text) {
  const doc = new DOMParser().parseFromString(text, 'application/xml');
  const robot = doc.documentElement;
  if (doc.querySelector('parsererror') || robot.nodeName !== 'robot') {
    throw new Error('not an SRDF file: expected an XML document whose root element is <robot>');
  }
  const poses = [...robot.children].filter((e) => e.nodeName === 'group_state').map((e) => e.getAttribute('name'));
  return { robot: robot.getAttribute('name'), poses: [...new Set(poses)] };
}

// The part of an SRDF that achd reads (its <robot name> and <group_state> elements, with
// their joints), as the text a page's link carries: an SRDF's collision pairs can make it
// many times longer. The poses read from it are those read from the whole file.
export function srdfGroupStates(text) {
  const doc = new DOMParser().parseFromString(text, 'application/xml');
  const robot = doc.documentElement;
  if (doc.querySelector('parsererror') || robot.nodeName !== 'robot') {
    throw new Error('not an SRDF file: expected an XML document whose root element is <robot>');
  }
  const out = document.implementation.createDocument(null, 'robot', null);
  const name = robot.getAttribute('name');
  if (name !== null) out.documentElement.setAttribute('name', name);
  for (const state of [...robot.children].filter((e) => e.nodeName === 'group_state')) {
    out.documentElement.append('\n  ', out.importNode(state, true));
  }
  out.documentElement.append('\n');
  return new XMLSerializer().serializeToString(out);
}
