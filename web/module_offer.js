// What this build of the achd module offers the page: its integrators (and which are
// adaptive), singularity policies, joint-limit policies, directions and effects
// (achd.constants, in the module's order) and the simulator's defaults and gravity, which
// the page uses as its own (a page opened without a hash runs what a scene or a JS
// simulator left at its defaults runs; the simulator's policy is in its solver options).

export function moduleOffer(achd) {
  const k = achd.constants;
  const d = k.simulator_options;
  return {
    integrators: [...k.integrators],
    policies: [...k.singularity_policies],
    limitPolicies: [...k.limit_policies],
    adaptiveIntegrators: [...k.adaptive_integrators],
    directions: [...k.directions],
    effects: Object.keys(k.effects),
    gravity: [...d.gravity],
    defaults: { integrator: d.integrator, policy: d.solver.policy, rtol: d.rtol, limits: d.limits },
  };
}
