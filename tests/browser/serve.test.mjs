// End-to-end test of `nurbs-box serve` in a real browser (Debian's chromium, driven by
// playwright-core): edit a curve with the mouse and check that the verified box follows it.
// Run through run.sh (it installs what is missing and builds the binary).
//
// Environment: NURBS_BOX_BIN (the binary), CHROMIUM (default /usr/bin/chromium),
// SCREENSHOT (default ../../results/serve_screenshot.png), ROUND_TRIP_LIMIT_MS (if set, a median
// limit of an edit's round trip for bezier and newton on a 100-point curve; unset, the times are
// only measured and printed: a shared, loaded machine must not turn a timing into a failure;
// headless Chromium rasterises the canvas in software and paces frames, see the README).
import { chromium } from 'playwright-core';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '../..');
const BIN = process.env.NURBS_BOX_BIN || path.join(root, 'target/release/nurbs-box');
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const SCREENSHOT = process.env.SCREENSHOT || path.join(root, 'results/serve_screenshot.png');
const LIMIT_MS = process.env.ROUND_TRIP_LIMIT_MS ? Number(process.env.ROUND_TRIP_LIMIT_MS) : Infinity;

let passed = 0;
let failed = 0;

function check(cond, what) {
  if (!cond) throw new Error(what);
}

async function step(name, f) {
  if (failed) {
    console.log(`skip - ${name}`);
    return;
  }
  try {
    await f();
    passed++;
    console.log(`ok - ${name}`);
  } catch (e) {
    failed++;
    console.log(`FAIL - ${name}: ${e.stack || e}`);
  }
}

// Start the server on a free port; resolve with its URL (printed on start).
function startServer() {
  const child = spawn(BIN, ['serve'], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let out = '';
    const timer = setTimeout(() => reject(new Error(`no address from ${BIN} serve within 10 s`)), 10000);
    child.on('error', reject);
    child.on('exit', (code) => reject(new Error(`${BIN} serve exited with ${code}`)));
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: m[0] });
      }
    });
  });
}

async function post(url, body) {
  const r = await fetch(url, { method: 'POST', body: JSON.stringify(body) });
  return { status: r.status, json: await r.json() };
}

// The box of `strategy` read back through the API contains the curve: the API's own samples,
// and verified enclosures of C(u) at `n` parameters from /api/eval.
async function checkContains(base, curve, strategy = 'newton', n = 64) {
  const r = await post(`${base}api/enclose?strategy=${strategy}&samples=2000`, curve);
  check(r.status === 200, `enclose answered ${r.status}: ${JSON.stringify(r.json)}`);
  const rec = r.json.records[0];
  check(rec.verified, 'the box is verified');
  const inside = (p) => p.every((x, j) => rec.lo[j] <= x && x <= rec.hi[j]);
  const out = r.json.samples.filter((p) => !inside(p));
  check(r.json.samples.length >= 1900 && out.length === 0, `${out.length} of ${r.json.samples.length} sampled points outside the box`);
  const [a, b] = r.json.domain;
  for (let i = 0; i <= n; i++) {
    const u = i === n ? b : a + ((b - a) * i) / n;
    const e = await post(`${base}api/eval?u=${u}`, curve);
    check(e.status === 200, `eval answered ${e.status}`);
    check(e.json.lo.every((lo, j) => rec.lo[j] <= lo && e.json.hi[j] <= rec.hi[j]), `C(${u}) is outside the box`);
  }
  // tight: the box touches the curve (certified gap tiny against the curve's size)
  const size = Math.max(...rec.hi.map((h, j) => h - rec.lo[j]));
  check(Math.max(...rec.gap) <= 1e-9 * Math.max(size, 1), `gap ${rec.gap} is not tight`);
  return rec;
}

function median(xs) {
  const s = [...xs].sort((x, y) => x - y);
  return s[Math.floor(s.length / 2)];
}

function quantile(xs, q) {
  const s = [...xs].sort((x, y) => x - y);
  return s[Math.min(s.length - 1, Math.floor(q * s.length))];
}

async function main() {
  const { child, url } = await startServer();
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'nurbs-box-chromium-'));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1280, height: 800 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      ...(process.env.CHROMIUM_EXTRA || '').split(' ').filter(Boolean)],
  });
  const page = context.pages()[0] || (await context.newPage());
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  page.on('console', (m) => m.type() === 'error' && pageErrors.push(m.text()));
  const settle = () => page.evaluate(() => window.nurbsBox.settle());
  const st = () => page.evaluate(() => {
    const s = window.nurbsBox.state;
    return { points: s.points, degree: s.degree, knots: s.knots, result: s.result, evalResult: s.evalResult, message: s.message };
  });
  const curve = () => page.evaluate(() => window.nurbsBox.curveJSON());
  const canvasBox = async () => page.locator('#canvas').boundingBox();
  const pointPx = async (i) => {
    const cb = await canvasBox();
    const [x, y] = await page.evaluate((i) => window.nurbsBox.toPx(window.nurbsBox.state.points[i]), i);
    return [cb.x + x, cb.y + y];
  };

  try {
    await step('the page loads with its controls', async () => {
      await page.goto(url);
      await page.waitForSelector('body[data-ready="true"]', { timeout: 10000 });
      check(await page.locator('#strategy option').count() >= 6, 'strategy list');
      check(await page.locator('#degree option').first().textContent() === '1', 'degrees start at 1');
    });

    await step('five clicks add five points, and a verified box appears that contains the curve', async () => {
      const cb = await canvasBox();
      const clicks = [[150, 500], [300, 200], [480, 560], [650, 230], [820, 480]];
      for (const [x, y] of clicks) {
        await page.mouse.click(cb.x + x, cb.y + y);
        await settle();
      }
      const s = await st();
      check(s.points.length === 5, `${s.points.length} points`);
      check(s.result && s.result.records.length === 1, `no box: ${s.message}`);
      const rec = s.result.records[0];
      check(rec.strategy === 'newton' && rec.verified, 'newton box');
      const apiRec = await checkContains(url, await curve());
      check(JSON.stringify(apiRec.lo) === JSON.stringify(rec.lo) && JSON.stringify(apiRec.hi) === JSON.stringify(rec.hi),
        'the page shows the box the API computes');
      // the box is drawn: its left edge has the strategy's colour on the canvas
      const px = await page.evaluate((rec) => {
        const nb = window.nurbsBox;
        const [x0, y0] = nb.toPx(rec.lo), [, y1] = nb.toPx(rec.hi);
        const c = document.getElementById('canvas').getContext('2d');
        const dpr = window.devicePixelRatio || 1;
        const d = c.getImageData(Math.round(x0 * dpr), Math.round(((y0 + y1) / 2) * dpr), 1, 1).data;
        return [d[0], d[1], d[2]];
      }, rec);
      check(px[0] > 150 && px[1] < 120 && px[2] < 120, `box edge pixel ${px} is not the newton red`);
    });

    await step('dragging a point moves the box with it', async () => {
      const before = (await st()).result.records[0];
      const [x, y] = await pointPx(1);
      await page.mouse.move(x, y);
      await page.mouse.down();
      for (let i = 1; i <= 10; i++) await page.mouse.move(x + 4 * i, y - 8 * i);
      await page.mouse.up();
      await settle();
      const s = await st();
      const rec = s.result.records[0];
      check(s.points.length === 5, 'still five points');
      check(rec.hi[1] > before.hi[1], `the box's top followed the point up (${before.hi[1]} -> ${rec.hi[1]})`);
      await checkContains(url, await curve());
    });

    await step('changing the degree re-knots the curve and re-encloses it', async () => {
      await page.selectOption('#degree', '2');
      await settle();
      const s = await st();
      check(s.degree === 2 && s.knots.length === 5 + 2 + 1, `degree ${s.degree}, ${s.knots.length} knots`);
      check(JSON.stringify(s.knots) === '[0,0,0,1,2,3,3,3]', `clamped uniform knots, got ${s.knots}`);
      await checkContains(url, await curve());
    });

    await step('right click deletes a point', async () => {
      const [x, y] = await pointPx(3);
      await page.mouse.click(x, y, { button: 'right' });
      await settle();
      const s = await st();
      check(s.points.length === 4, `${s.points.length} points`);
      check(s.result, `no box: ${s.message}`);
      await checkContains(url, await curve());
    });

    await step('insert at an index through the form', async () => {
      const p0 = (await st()).points[0];
      await page.fill('#ins-index', '1');
      await page.fill('#ins-x', String(p0[0] + 1));
      await page.fill('#ins-y', String(p0[1] - 3));
      await page.fill('#ins-w', '2');
      await page.click('#insert-form button[type=submit]');
      await settle();
      const s = await st();
      check(s.points.length === 5 && s.points[1][1] === p0[1] - 3, 'inserted at index 1');
      const c = await curve();
      check(c.weights && c.weights[1] === 2, 'rational with weight 2');
      await checkContains(url, c);
    });

    await step('the slider shows C(u) and its de Boor points', async () => {
      await page.locator('#u-slider').fill('300');
      await page.waitForFunction(() => {
        const e = window.nurbsBox.state.evalResult;
        return e && Math.abs(e.param - 0.3 * e.domain[1]) < 1e-9;
      });
      const e = (await st()).evalResult;
      check(e.de_boor.length === 3 && e.de_boor[0].length === 3 && e.de_boor[2].length === 1, 'de Boor triangle of degree 2');
      check(e.de_boor[2][0].every((x, j) => Math.abs(x - e.point[j]) < 1e-12), 'the last level is C(u)');
    });

    await step("every strategy's box, with its time and gap; screenshot", async () => {
      await page.check('#show-all');
      await page.check('#show-coords');
      await settle();
      const s = await st();
      check(s.result.records.length === 6, `${s.result.records.length} boxes`);
      for (const rec of s.result.records) check(typeof rec.time_s === 'number' && rec.gap.length === 2, rec.strategy);
      check(await page.locator('#result tr').count() >= 7, 'the table lists every strategy');
      await page.locator('#help-button').click();
      check(await page.locator('#help').isVisible(), 'help opens');
      check((await page.locator('#help').textContent()).includes('Degree 0'), 'help explains degree >= 1');
      await page.locator('#help-close').click();
      fs.mkdirSync(path.dirname(SCREENSHOT), { recursive: true });
      await page.screenshot({ path: SCREENSHOT });
      console.log(`# screenshot: ${path.relative(process.cwd(), SCREENSHOT)}`);
      await page.uncheck('#show-all');
      await page.uncheck('#show-coords');
    });

    await step(`an edit's round trip on a 100-point curve (measured${Number.isFinite(LIMIT_MS) ? `; median < ${LIMIT_MS} ms` : ''})`, async () => {
      const pts = [];
      for (let i = 0; i < 100; i++) pts.push([i / 5, 3 * Math.sin(i / 4) + Math.cos(i / 1.7)]);
      await page.evaluate((pts) => window.nurbsBox.setCurve({ degree: 3, control_points: pts }), pts);
      await page.uncheck('#show-deboor');
      await settle();
      check((await st()).result, 'the 100-point curve has a box');
      const lines = [];
      let worst = 0;
      for (const strategy of ['bezier', 'newton']) {
        await page.selectOption('#strategy', strategy);
        await settle();
        const times = await page.evaluate(async ({ pts }) => {
          const nb = window.nurbsBox;
          nb.state.roundTrips.length = 0;
          const wall = [], split = [];
          for (let k = 0; k < 260; k++) {
            const i = 10 + (k % 80);
            const t0 = performance.now();
            await nb.movePoint(i, [pts[i][0], pts[i][1] + 0.5 * Math.sin(k)]);
            wall.push(performance.now() - t0);
            split.push(nb.state.lastSplit);
          }
          // the request and its verified box alone, over the page's WebSocket, no redraw
          const body = JSON.stringify(nb.curveJSON());
          const api = [];
          for (let k = 0; k < 100; k++) {
            const t0 = performance.now();
            await nb.api(`/api/enclose?strategy=${nb.state.result.records[0].strategy}`, body);
            api.push(performance.now() - t0);
          }
          return { api, rt: nb.state.roundTrips.slice(60), wall: wall.slice(60), split: split.slice(60), server: nb.state.result.records[0].time_s };
        }, { pts });
        const m = median(times.rt);
        lines.push(`# ${strategy}: request + verified box alone (WebSocket, no redraw): median ${median(times.api).toFixed(2)} ms; ` +
          `in the edit loop: reply ${median(times.split.map((x) => x[0])).toFixed(2)} ms + draw ${median(times.split.map((x) => x[1])).toFixed(2)} ms`);
        worst = Math.max(worst, m);
        lines.push(`# round trip ${strategy}: median ${m.toFixed(2)} ms, p90 ${quantile(times.rt, 0.9).toFixed(2)} ms, ` +
          `max ${Math.max(...times.rt).toFixed(2)} ms over ${times.rt.length} edits (request + verified box + redraw; ` +
          `strategy alone ${(times.server * 1e3).toFixed(3)} ms)`);
      }
      for (const l of lines) console.log(l);
      check(worst < LIMIT_MS, `median round trip ${worst.toFixed(2)} ms`);
    });

    await step('no errors in the page', async () => {
      check(pageErrors.length === 0, pageErrors.join('\n'));
    });
  } finally {
    await context.close();
    child.kill();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

main().catch((e) => {
  console.log(`FAIL - setup: ${e.stack || e}`);
  console.log(`${passed} passed, ${failed + 1} failed`);
  process.exit(1);
});
