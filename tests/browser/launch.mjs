// Serves the repository on a free localhost port and opens the demo page in Debian's
// Chromium through playwright-core, recording every console error and page error.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';
import { serve } from '../../scripts/serve.mjs';

export const CHROMIUM = process.env.ACHD_CHROMIUM ?? '/usr/bin/chromium';

export async function openPage({ hash = '', viewport = { width: 1400, height: 1100 } } = {}) {
  const { server, url } = await serve({ port: 0 });
  const profile = await mkdtemp(join(tmpdir(), 'achd-chromium-'));
  // playwright-core takes the profile directory as an argument of its own.
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    viewport,
    // A fresh profile and no background traffic: the page must work with localhost only.
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      // Chromium no longer falls back to its software WebGL on its own; the 3D view needs it.
      '--enable-unsafe-swiftshader',
    ],
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const consoleErrors = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') consoleErrors.push(msg.text());
  });
  page.on('pageerror', (err) => consoleErrors.push(`page error: ${err.message}`));
  await page.goto(url + hash);
  await page.evaluate(() => window.achdDemo.ready);
  return {
    page,
    url,
    consoleErrors,
    async close() {
      await context.close();
      await new Promise((resolve) => server.close(resolve));
      await rm(profile, { recursive: true, force: true });
    },
  };
}
