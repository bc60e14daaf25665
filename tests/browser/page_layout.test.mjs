// The controls fit their cards, in Chromium: in the window of the screenshots (docs/screenshots)
// (1400 x 1000) and in a narrow one (1024 px wide, still two columns), every element and
// every text of the tip-directions card lies inside the card's content box (its bounding
// box against the card's less its border and padding): as the page opens, at README.md's
// UR5 link after 12 simulated seconds (y accelerated, a direction possibly lost), and
// with every row marked lost; no console errors.
import assert from 'node:assert/strict';
import test from 'node:test';
import { openPage } from './launch.mjs';

const BOUNDARY_HASH = '#robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping,friction,external_wrenches' +
  '&dirs=z:hold,rx:hold,y:0.5';
const WINDOWS = [{ width: 1400, height: 1000 }, { width: 1024, height: 768 }];
// Subpixel layout: a box may end a fraction of a pixel past another it fits in.
const SLACK = 0.5;

// What of the directions card lies outside its content box: ['TD.x 1325.3..1378.3 of 1090.2..1373.8', ...].
function overflowing(slack) {
  const card = document.getElementById('directions').closest('.card');
  const box = card.getBoundingClientRect();
  const style = getComputedStyle(card);
  const inner = {
    left: box.left + parseFloat(style.borderLeftWidth) + parseFloat(style.paddingLeft),
    right: box.right - parseFloat(style.borderRightWidth) - parseFloat(style.paddingRight),
    top: box.top + parseFloat(style.borderTopWidth) + parseFloat(style.paddingTop),
    bottom: box.bottom - parseFloat(style.borderBottomWidth) - parseFloat(style.paddingBottom),
  };
  const out = [];
  const walker = document.createTreeWalker(card, NodeFilter.SHOW_ELEMENT | NodeFilter.SHOW_TEXT);
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    let b;
    if (node.nodeType === Node.TEXT_NODE) {
      if (!node.textContent.trim()) continue;
      const range = document.createRange();
      range.selectNodeContents(node);
      b = range.getBoundingClientRect();
    } else {
      b = node.getBoundingClientRect();
    }
    if (!b.width && !b.height) continue;  // not rendered (hidden)
    if (b.left < inner.left - slack || b.right > inner.right + slack || b.top < inner.top - slack || b.bottom > inner.bottom + slack) {
      const name = node.nodeType === Node.TEXT_NODE ? JSON.stringify(node.textContent)
        : `${node.tagName}${node.className ? `.${node.className}` : ''}`;
      out.push(`${name} ${b.left.toFixed(1)}..${b.right.toFixed(1)} x ${b.top.toFixed(1)}..${b.bottom.toFixed(1)} ` +
        `of ${inner.left.toFixed(1)}..${inner.right.toFixed(1)} x ${inner.top.toFixed(1)}..${inner.bottom.toFixed(1)}`);
    }
  }
  return out;
}

for (const viewport of WINDOWS) {
  test(`the tip-directions card holds its rows in a ${viewport.width} x ${viewport.height} window`, async (t) => {
    const session = await openPage({ viewport, hash: BOUNDARY_HASH });
    const { page, consoleErrors } = session;
    const check = async (when) => assert.deepEqual(await page.evaluate(overflowing, SLACK), [], `${when}: outside the card`);
    try {
      // Two columns (the view and the controls) at both widths.
      const columns = await page.evaluate(() => getComputedStyle(document.querySelector('.layout')).gridTemplateColumns.split(' ').length);
      assert.equal(columns, 2);
      await t.test('as the page opens, y accelerated', () => check('at the start'));
      await t.test('after 12 s at the workspace boundary', async () => {
        await page.evaluate(() => window.achdDemo.pause());
        for (let k = 0; k < 12; k++) await page.evaluate(() => window.achdDemo.step(1000));
        const lost = await page.locator('#directions tr.lost').count();
        t.diagnostic(`${lost} direction(s) lost`);
        await check('after 12 s');
      });
      await t.test('every row marked lost', async () => {
        await page.evaluate(() => {
          for (const tag of document.querySelectorAll('#directions .lost-tag')) tag.hidden = false;
        });
        await check('every row lost');
      });
      assert.deepEqual(consoleErrors, []);
    } finally {
      await session.close();
    }
  });
}
