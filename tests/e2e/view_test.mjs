// The view in a real browser (Debian's Chromium through playwright-core): the page loads the
// scene, a statement typed in its query box highlights exactly the engine's hits (in the page's
// state and in the drawn frame), hovering a hit shows its path, GUIDE draws a numbered route, the
// floor plan toggles, the standalone page of `smql export html` opens from a file without a query box,
// every thing labelled or in the key, labels apart and legible, categories' colours apart,
// and a browser without WebGL is told so where the scene would be.
// A captured scene's page draws the capture's points, and its Points button hides them.
//   node view_test.mjs URL EXPECTED_IDS_JSON STANDALONE_HTML SHOT_DIR CAPTURED_HTML
import { writeFile } from 'node:fs/promises';
import { chromium } from '../../web/node_modules/playwright-core/index.mjs';

const [url, expectedText, standalone, shots, captured] = process.argv.slice(2);
const expected = JSON.parse(expectedText).sort((a, b) => a - b);
let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
};

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  await page.waitForFunction(() => window.smqlView && (window.smqlView.ready || window.smqlView.error), null, { timeout: 60000 });
  let state = await page.evaluate(() => ({ ...window.smqlView }));
  check(state.ready && !state.error, `the page loaded scene ${state.scene} (${state.nodes} nodes)`);
  check(state.nodes > 50, 'the Replica room has more than 50 nodes to draw');
  await page.screenshot({ path: `${shots}/before.png` });

  // Labels: every thing of the room named on screen or in the key under the legend; labels never
  // overlap, stay inside the drawing and keep their size when the view zooms in.
  const readLabels = () => page.evaluate(() => {
    const v = window.smqlView;
    const drawn = [...document.querySelectorAll('#labels .label')].map((e) => {
      const r = e.getBoundingClientRect();
      return { id: Number(e.dataset.id), text: e.textContent, left: r.left, top: r.top, width: r.width,
        height: r.height, font: parseFloat(getComputedStyle(e).fontSize), clipped: e.scrollWidth > e.clientWidth };
    });
    const canvas = document.getElementById('canvas').getBoundingClientRect();
    return { drawn, unlabelled: v.unlabelled, key: document.querySelector('#key div').textContent,
      things: v.things, canvas: { left: canvas.left, top: canvas.top, right: canvas.right, bottom: canvas.bottom } };
  });
  const checkLabels = (labels, when) => {
    const named = new Set([...labels.drawn.map((l) => l.id), ...labels.unlabelled]);
    const missing = labels.things.filter((t) => !named.has(t.id));
    check(missing.length === 0, `${when}: all ${labels.things.length} things are labelled (${labels.drawn.length}) or in the key (${labels.unlabelled.length})`);
    check(labels.drawn.length >= 15, `${when}: at least 15 labels on screen (${labels.drawn.length})`);
    const byId = new Map(labels.things.map((t) => [t.id, t.category]));
    check(labels.drawn.every((l) => l.text === byId.get(l.id)), `${when}: each label names its thing's category`);
    check(labels.unlabelled.every((id) => labels.key.includes(`${byId.get(id)}#${id}`)), `${when}: the key names each thing not labelled`);
    let overlapping = 0;
    for (let i = 0; i < labels.drawn.length; i += 1)
      for (let j = i + 1; j < labels.drawn.length; j += 1) {
        const [a, b] = [labels.drawn[i], labels.drawn[j]];
        if (a.left < b.left + b.width && b.left < a.left + a.width && a.top < b.top + b.height && b.top < a.top + a.height) overlapping += 1;
      }
    check(overlapping === 0, `${when}: no two labels overlap (${overlapping})`);
    const c = labels.canvas;
    check(labels.drawn.every((l) => l.left >= c.left - 0.5 && l.top >= c.top - 0.5 && l.left + l.width <= c.right + 0.5 && l.top + l.height <= c.bottom + 0.5),
      `${when}: every label lies inside the drawing`);
    check(labels.drawn.every((l) => l.font >= 12 && !l.clipped), `${when}: labels are 12 px text, none cut off`);
  };
  const labels = await readLabels();
  checkLabels(labels, 'the whole room');
  await writeFile(`${shots}/labels.json`, JSON.stringify(labels.drawn));
  // The categories' colours: no two of the room alike (CIE delta E 1976 of at least 20).
  const colours = await page.evaluate(() => window.smqlView.colours);
  const lab = (hex) => {
    const [r, g, b] = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255)
      .map((v) => (v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4));
    const xyz = [(0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, 0.2126 * r + 0.7152 * g + 0.0722 * b,
      (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883].map((t) => (t > 216 / 24389 ? Math.cbrt(t) : (24389 / 27 * t + 16) / 116));
    return [116 * xyz[1] - 16, 500 * (xyz[0] - xyz[1]), 200 * (xyz[1] - xyz[2])];
  };
  const names = Object.keys(colours);
  let closest = { d: Infinity };
  for (let i = 0; i < names.length; i += 1)
    for (let j = i + 1; j < names.length; j += 1) {
      const [p, q] = [lab(colours[names[i]]), lab(colours[names[j]])];
      const d = Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
      if (d < closest.d) closest = { d, pair: `${names[i]} and ${names[j]}` };
    }
  check(names.length >= 20 && closest.d >= 20,
    `the ${names.length} categories' colours stay apart: the closest, ${closest.pair}, are ${closest.d.toFixed(1)} delta E apart`);
  // Zoomed in: fewer things in the picture, the rest in the key, labels the same size.
  const middle = await page.evaluate(() => { const r = document.getElementById('canvas').getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; });
  await page.mouse.move(middle.x, middle.y);
  for (let i = 0; i < 6; i += 1) await page.mouse.wheel(0, -400);
  await page.waitForTimeout(400);
  checkLabels(await readLabels(), 'zoomed in');
  await page.screenshot({ path: `${shots}/zoomed.png` });
  for (let i = 0; i < 6; i += 1) await page.mouse.wheel(0, 400);
  await page.waitForTimeout(400);

  const statement = 'FIND cushion WHERE on(sofa)';
  await page.fill('#statement', statement);
  await page.click('#run');
  await page.waitForFunction((s) => window.smqlView.statement === s && (window.smqlView.highlighted.length > 0 || window.smqlView.error), statement, { timeout: 30000 });
  await page.waitForTimeout(300);  // a frame or two drawn with the highlight
  state = await page.evaluate(() => ({ hits: window.smqlView.hits, highlighted: window.smqlView.highlighted, error: window.smqlView.error }));
  const hits = [...state.hits].sort((a, b) => a - b);
  const highlighted = [...state.highlighted].sort((a, b) => a - b);
  check(!state.error, `${statement} ran in the page`);
  check(JSON.stringify(hits) === JSON.stringify(expected), `its hits are the engine's: ${hits} = ${expected}`);
  check(JSON.stringify(highlighted) === JSON.stringify(expected), `exactly those are highlighted: ${highlighted}`);
  const rows = await page.locator('#answer table tr').count();
  check(rows === expected.length + 1, `the answer panel lists ${rows - 1} rows`);
  await page.screenshot({ path: `${shots}/after.png` });

  // Hovering a highlighted cushion shows its path.
  const at = await page.evaluate((id) => window.smqlView.screenOf(id), expected[0]);
  await page.mouse.move(at.x, at.y);
  await page.waitForTimeout(200);
  const tip = await page.locator('#tooltip').textContent();
  check(await page.locator('#tooltip').isVisible() && tip.includes('cushion#') && tip.includes('replica-room0 / '),
    `hovering shows the path: ${tip.slice(0, 80)}`);

  // GUIDE: a route with numbered steps, the goal highlighted.
  await page.fill('#statement', 'GUIDE FROM door TO sofa#50');
  await page.click('#run');
  await page.waitForFunction(() => window.smqlView.statement.startsWith('GUIDE') && (window.smqlView.route.length > 0 || window.smqlView.error), null, { timeout: 30000 });
  state = await page.evaluate(() => ({ route: window.smqlView.route, highlighted: window.smqlView.highlighted }));
  check(state.route.length >= 3 && state.route[0].step === 0, `GUIDE draws a route of ${state.route.length} steps`);
  check(JSON.stringify(state.highlighted) === '[50]', 'and highlights its goal, sofa#50');
  const panel = await page.evaluate(() => {
    const answer = document.getElementById('answer');
    const cells = [...answer.querySelectorAll('td')].map((td) => td.textContent);
    return { cells, fits: answer.querySelector('table').scrollWidth <= answer.clientWidth };
  });
  const long = panel.cells.filter((c) => /^-?\d+\.\d{3,}$/.test(c));
  check(long.length === 0, `GUIDE's figures are rounded (${long.slice(0, 3).join(', ') || 'none longer than 2 decimals'})`);
  check(panel.fits, 'and its table fits the panel, no column cut off');

  // A mistake shows the engine's error, caret and hint.
  await page.fill('#statement', 'FIND cushon');
  await page.click('#run');
  await page.waitForFunction(() => window.smqlView.error, null, { timeout: 30000 });
  const error = await page.locator('#answer .error').textContent();
  check(error.includes('did you mean cushion?'), 'an error shows its hint');

  await page.click('#plan');
  check((await page.evaluate(() => window.smqlView.mode)) === 'plan', 'the floor plan toggles on');
  await page.screenshot({ path: `${shots}/plan.png` });
  check(errors.length === 0, `no script errors (${errors.join('; ')})`);

  // The standalone page: the same scene from a file, no server.
  const file = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  await file.goto(`file://${standalone}`);
  await file.waitForFunction(() => window.smqlView && (window.smqlView.ready || window.smqlView.error), null, { timeout: 60000 });
  const offline = await file.evaluate(() => ({ ready: window.smqlView.ready, nodes: window.smqlView.nodes, error: window.smqlView.error }));
  check(offline.ready && offline.nodes === (await page.evaluate(() => window.smqlView.nodes)),
    `smql export html opens from a file with the same ${offline.nodes} nodes`);
  await file.screenshot({ path: `${shots}/standalone.png` });
  check(await file.evaluate(() => getComputedStyle(document.getElementById('query')).display === 'none'),
    'the standalone page shows no query box (it has no server to ask)');

  // A captured scene: its points drawn under the boxes, the Points button shows and hides them.
  const room = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  await room.goto(`file://${captured}`);
  await room.waitForFunction(() => window.smqlView && (window.smqlView.ready || window.smqlView.error), null, { timeout: 60000 });
  const points = await room.evaluate(() => window.smqlView.points);
  check(points > 1000 && await room.locator('#points').isVisible(), `a captured scene's page has its ${points} points and a Points button`);
  check(!(await file.locator('#points').isVisible()), 'an imported layout, which has no points, has no Points button');
  await room.waitForTimeout(300);
  await room.screenshot({ path: `${shots}/points-on.png` });
  await room.click('#points');
  await room.waitForTimeout(300);
  await room.screenshot({ path: `${shots}/points-off.png` });

  // A browser without WebGL: the page says so, where the scene would be.
  const blind = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  await blind.addInitScript(() => {
    const getContext = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (type, ...rest) {
      return /webgl/i.test(type) ? null : getContext.call(this, type, ...rest);
    };
  });
  await blind.goto(`file://${standalone}`);
  await blind.waitForFunction(() => window.smqlView && window.smqlView.error, null, { timeout: 60000 });
  const said = await blind.evaluate(() => document.getElementById('canvas').innerText);
  check(/no WebGL/.test(said) && /smql map/.test(said), `without WebGL the page says so ("${said.slice(0, 40)}...")`);
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
