// What this build of the achd module offers the page: its integrators and singularity
// policies (achd.constants, in the module's order) and the simulator's defaults, which
// the page uses as its own (a page opened without a hash runs what a scene or a JS
// simulator left at its defaults runs).
//
// Until issue 14's branches are merged, the module's simulator may not take the
// `policy` and `rtol` options; the page then hides those controls and leaves them out of
// the hash. `takesOption` finds out by creating a simulator of a one-joint robot with the
// option. After the merge both are always taken: replace `takesOption(...)` below by
// `true` and delete takesOption and PROBE_URDF.

const PROBE_URDF = `<robot name="probe"><link name="base"/>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>`;

export function moduleOffer(achd) {
  const k = achd.constants;
  const d = k.simulator_options;
  const policy = d.policy ?? d.solver.policy;
  const takesPolicy = takesOption(achd, { policy });
  const takesRtol = d.rtol !== undefined && takesOption(achd, { rtol: d.rtol });
  return {
    integrators: [...k.integrators],
    policies: takesPolicy ? [...k.singularity_policies] : [],
    defaults: {
      integrator: d.integrator,
      policy: takesPolicy ? policy : null,
      rtol: takesRtol ? d.rtol : null,
    },
  };
}

function takesOption(achd, options) {
  const robot = achd.loadURDF(PROBE_URDF, { root: 'base', tip: 'arm' });
  try {
    robot.createSimulator(options).delete();
    return true;
  } catch (err) {
    if (/unknown field/.test(err.message)) return false;
    throw err;
  } finally {
    robot.delete();
  }
}
