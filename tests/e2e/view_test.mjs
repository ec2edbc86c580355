// The view in a real browser (Debian's Chromium through playwright-core): the page loads the
// scene, a statement typed in its query box highlights exactly the engine's hits (in the page's
// state and in the drawn frame), hovering a hit shows its path, GUIDE draws a numbered route, the
// floor plan toggles, the standalone page of `smql export html` opens from a file without a query box,
// and a browser without WebGL is told so where the scene would be.
//   node view_test.mjs URL EXPECTED_IDS_JSON STANDALONE_HTML SHOT_DIR
import { chromium } from '../../web/node_modules/playwright-core/index.mjs';

const [url, expectedText, standalone, shots] = process.argv.slice(2);
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
