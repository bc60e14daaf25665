// Writes the README's screenshots of the demo page, from Debian's Chromium:
//   docs/screenshots/default.png  the default robot as the page opens, swinging under gravity
//   docs/screenshots/held.png     the same robot with x, z, rx and ry held: the tip keeps its
//                                 height and tilt while gravity swings it along y
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
