// Writes the README's screenshots of the demo page, from Debian's Chromium:
//   docs/screenshots/default.png  the default robot as the page opens, swinging under gravity
//   docs/screenshots/held.png     the same robot with x, z, rx and ry held: the tip keeps its
//                                 height and tilt while gravity swings it along y
//   docs/screenshots/boundary.png README.md's UR5 link (z and rx held, y accelerated at
//                                 0.5 m/s²) after 12 simulated seconds: the tip has reached
//                                 the workspace boundary, the events notice says what the
//                                 simulator did about y
// Usage: node tests/browser/screenshots.mjs   (after the wasm build)
import { mkdir } from 'node:fs/promises';
import { openPage } from './launch.mjs';

const out = new URL('../../docs/screenshots/', import.meta.url);
await mkdir(out, { recursive: true });

const session = await openPage({ viewport: { width: 1400, height: 1000 } });
try {
  const { page } = session;
  await page.waitForTimeout(1500);
  await page.screenshot({ path: new URL('default.png', out).pathname });

  await page.evaluate(() => {
    const demo = window.achdDemo;
    demo.setDirection('x', 'hold');
    demo.setDirection('z', 'hold');
    demo.setDirection('rx', 'hold');
    demo.setDirection('ry', 'hold');
  });
  await page.waitForTimeout(2500);
  await page.screenshot({ path: new URL('held.png', out).pathname });
  if (session.consoleErrors.length) throw new Error(`console errors: ${session.consoleErrors.join('\n')}`);
} finally {
  await session.close();
}

const boundary = await openPage({
  viewport: { width: 1400, height: 1000 },
  hash: '#robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping,friction,external_wrenches' +
    '&dirs=z:hold,rx:hold,y:0.5',
});
try {
  const { page } = boundary;
  // 12 s at once (a step that fails is shown on the page, and so is in the picture).
  await page.evaluate(() => {
    window.achdDemo.pause();
    try {
      window.achdDemo.step(12000);
    } catch {
      return;
    }
    window.achdDemo.play();
  });
  await page.waitForTimeout(1500);
  await page.screenshot({ path: new URL('boundary.png', out).pathname });
  if (boundary.consoleErrors.length) throw new Error(`console errors: ${boundary.consoleErrors.join('\n')}`);
} finally {
  await boundary.close();
}
