// Opens feedplan's HTML reports in headless Chromium (puppeteer-core, pinned in report/web/package-lock.json)
// and checks them as a user sees them: no console error and no request leaving the file (the report opens
// offline), the charts and values the page must show, a hover readout on the tool path against the plan
// CSV written by the same run, and zoom linked across the charts. Saves screenshots into --shots.
//
// node report_browser_test.mjs --web-dir DIR --chromium PATH --shots DIR
//      [--plan PLAN.html --csv PLAN.csv] [--report REPORT.html] [--history HISTORY.html --cycles N]
//      [--learn LEARN.html --learn-cycles N]
//      [--comparison COMPARE.html --compare-json COMPARE.json]
// Exits 0 when every check passes, 1 with every failure listed otherwise.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const require = createRequire(path.resolve(args['web-dir'], 'package.json'));
const puppeteer = require('puppeteer-core');

const failures = [];
function check(condition, what) {
  if (!condition) failures.push(what);
  console.log((condition ? 'ok   ' : 'FAIL ') + what);
}

function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const header = lines[0].split(',');
  return lines.slice(1).map((line) => {
    const cells = line.split(',');
    const row = {};
    header.forEach((h, k) => { row[h] = cells[k]; });
    return row;
  });
}

// Opens `file`, collecting console errors, page errors and requests that leave the file.
async function open(browser, file, label) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1400, height: 900 });
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push('console error: ' + m.text()); });
  page.on('pageerror', (e) => problems.push('page error: ' + e.message));
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) problems.push('request: ' + r.url()); });
  await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => window.feedplanReport && window.feedplanReport.ready, { timeout: 20000 })
    .catch(() => problems.push('the page never became ready'));
  return { page, problems, label };
}

function finish(opened) {
  check(opened.problems.length === 0, opened.label + ': no console errors, page errors or outside requests' +
        (opened.problems.length ? ' (' + opened.problems.join('; ') + ')' : ''));
}

async function shot(page, name) {
  fs.mkdirSync(args.shots, { recursive: true });
  const file = path.join(args.shots, name + '.png');
  await page.screenshot({ path: file, fullPage: true });
  console.log('screenshot: ' + file);
}

async function chartsPresent(page, ids, label) {
  for (const id of ids) {
    const n = await page.$$eval('#' + id + ' canvas', (c) => c.length);
    check(n > 0, label + ': chart #' + id + ' is drawn');
  }
}

// The number as the page shows it against the CSV's text: equal to the CSV's last digit.
function sameNumber(shown, csvText, decimals) {
  const a = Number(shown), b = Number(csvText);
  return Number.isFinite(a) && Number.isFinite(b) && Math.abs(a - b) <= 0.51 * Math.pow(10, -decimals);
}

async function checkPlan(browser) {
  const opened = await open(browser, args.plan, 'plan');
  const { page } = opened;
  const csv = readCsv(args.csv);
  const sampleCount = await page.evaluate(() => JSON.parse(document.getElementById('report-data').textContent).samples.s_mm.length);
  check(sampleCount === csv.length, 'plan: the page carries every CSV row (' + sampleCount + ' samples, CSV ' + csv.length + ')');
  await chartsPresent(page, ['chart-force', 'chart-feed', 'chart-engagement'], 'plan');
  check(await page.$('#path-canvas') !== null, 'plan: the tool path is drawn');
  const summary = await page.$$eval('#summary tr', (rows) => rows.map((r) => [r.cells[0].textContent, r.cells[1].textContent]));
  const cycle = summary.find(([k]) => k === 'cycle time, planned');
  check(cycle !== undefined, 'plan: the summary shows the planned cycle time');
  const lastTime = Number(csv[csv.length - 1].time_s);
  check(cycle && Number.parseFloat(cycle[1]) >= lastTime - 0.01,
        'plan: the cycle time (' + (cycle && cycle[1]) + ') is at least the last sample\'s time in the CSV (' + lastTime + ' s)');
  const forceLabels = await page.evaluate(() => window.feedplanReport.charts['chart-force'].series.map((s) => s.label));
  check(forceLabels.includes('target [N]') && forceLabels.includes('upper bound [N]'),
        'plan: the force chart has the target and the uncertainty band (' + forceLabels.join(', ') + ')');
  const feedLabels = await page.evaluate(() => window.feedplanReport.charts['chart-feed'].series.map((s) => s.label));
  check(feedLabels.includes('machine max [mm/min]') && feedLabels.includes('machine min [mm/min]'),
        'plan: the feed chart has the machine limits');
  await shot(page, 'plan');

  // Hover: point at the engaged sample with the largest predicted force (found in the CSV, not the page).
  let target = -1;
  csv.forEach((row, i) => {
    if (row.engaged === '1' && (target < 0 || Number(row.predicted_force_n) > Number(csv[target].predicted_force_n))) target = i;
  });
  await page.$eval('#path-canvas', (e) => e.scrollIntoView({ block: 'center' }));
  const point = await page.evaluate((i) => window.feedplanReport.pathClientPoint(i), target);
  await page.mouse.move(point.x, point.y);
  const readout = await page.$$eval('#readout td', (cells) => {
    const out = {};
    for (const c of cells) out[c.dataset.field] = c.textContent;
    out.sample = document.getElementById('readout').dataset.sample;
    return out;
  });
  const j = Number(readout.sample);
  check(Number.isInteger(j) && j >= 0 && j < csv.length, 'plan: pointing at the path selects a sample (' + readout.sample + ')');
  if (Number.isInteger(j) && j >= 0 && j < csv.length) {
    const row = csv[j];
    const mmPerPx = await page.evaluate(() => 1 / window.feedplanReport.pathScale());
    const dx = Number(row.x_mm) - Number(csv[target].x_mm), dy = Number(row.y_mm) - Number(csv[target].y_mm);
    check(Math.hypot(dx, dy) <= 1.5 * mmPerPx, 'plan: the sample read out (' + j + ') lies under the pointer (at sample ' + target + ')');
    check(sameNumber(readout.s_mm, row.s_mm, 4), 'plan: hover s = ' + readout.s_mm + ' mm, CSV ' + row.s_mm);
    check(sameNumber(readout.engagement_deg, row.engagement_deg, 4), 'plan: hover engagement = ' + readout.engagement_deg + ' deg, CSV ' + row.engagement_deg);
    check(sameNumber(readout.chip_thickness_mm, row.chip_thickness_mm, 6), 'plan: hover t_m = ' + readout.chip_thickness_mm + ' mm, CSV ' + row.chip_thickness_mm);
    check(sameNumber(readout.contact_length_mm, row.contact_length_mm, 4), 'plan: hover L = ' + readout.contact_length_mm + ' mm, CSV ' + row.contact_length_mm);
    check(sameNumber(readout.feed_mm_per_min, row.feed_mm_per_min, 3), 'plan: hover feed = ' + readout.feed_mm_per_min + ' mm/min, CSV ' + row.feed_mm_per_min);
    check(sameNumber(readout.predicted_force_n, row.predicted_force_n, 3), 'plan: hover predicted force = ' + readout.predicted_force_n + ' N, CSV ' + row.predicted_force_n);
    check(readout.limit_reason.startsWith(row.limit_reason), 'plan: hover limit "' + readout.limit_reason + '", CSV "' + row.limit_reason + '"');
  }
  await shot(page, 'plan-hover');

  // Zoom one chart by dragging across the middle third of it: every chart follows.
  const over = await page.$('#chart-feed .u-over');
  await over.evaluate((e) => e.scrollIntoView({ block: 'center' }));
  const box = await over.boundingBox();
  await page.mouse.move(box.x + box.width / 3, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2, { steps: 5 });
  await page.mouse.move(box.x + 2 * box.width / 3, box.y + box.height / 2, { steps: 5 });
  await page.mouse.up();
  const scales = await page.evaluate(() => ['chart-force', 'chart-feed', 'chart-engagement'].map((id) => {
    const x = window.feedplanReport.charts[id].scales.x;
    return [x.min, x.max];
  }));
  const full = Number(csv[csv.length - 1].s_mm) - Number(csv[0].s_mm);
  check(scales[1][1] - scales[1][0] < 0.5 * full, 'plan: dragging across the feed chart zooms it (' + scales[1].map((v) => v.toFixed(2)).join('–') + ' mm of ' + full.toFixed(2) + ')');
  check(scales.every(([a, b]) => Math.abs(a - scales[1][0]) < 1e-6 && Math.abs(b - scales[1][1]) < 1e-6),
        'plan: the force and engagement charts follow the zoom');
  await shot(page, 'plan-zoomed');
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2, { clickCount: 2 });
  const reset = await page.evaluate(() => window.feedplanReport.charts['chart-engagement'].scales.x);
  check(Math.abs(reset.max - reset.min - full) < 1e-6, 'plan: a double-click shows the whole path again (' +
        reset.min.toFixed(2) + '–' + reset.max.toFixed(2) + ' mm)');
  await page.select('#path-colour', 'predicted');
  await shot(page, 'plan-by-force');
  finish(opened);
  await page.close();
}

async function checkReport(browser) {
  const opened = await open(browser, args.report, 'report');
  await chartsPresent(opened.page, ['chart-force', 'chart-feed', 'chart-engagement'], 'report');
  if (args.csv) {
    const csv = readCsv(args.csv);
    const n = await opened.page.evaluate(() => JSON.parse(document.getElementById('report-data').textContent).samples.s_mm.length);
    check(n === csv.length, 'report: the plan re-made from the plan report has the CSV\'s ' + csv.length + ' samples (' + n + ')');
  }
  await shot(opened.page, 'report');
  finish(opened);
  await opened.page.close();
}

async function checkHistory(browser, file, cycles, label) {
  const opened = await open(browser, file, label);
  const { page } = opened;
  await chartsPresent(page, ['chart-force', 'chart-feed', 'chart-engagement', 'chart-cycles', 'chart-history-force', 'chart-history-feed'], label);
  const rows = await page.$$eval('#cycle-table tr', (r) => r.length - 1);
  check(rows === cycles, label + ': the cycle table has one row per cycle (' + rows + ' of ' + cycles + ')');
  const overlaid = await page.evaluate(() => window.feedplanReport.charts['chart-history-force'].series.length);
  check(overlaid === cycles + 2, label + ': every cycle\'s measured peaks are overlaid (' + (overlaid - 2) + ' curves)');
  const perCycle = await page.evaluate(() => window.feedplanReport.charts['chart-cycles'].data[0].length);
  check(perCycle === cycles, label + ': peak error and cycle time per cycle (' + perCycle + ' points)');
  await shot(page, label);
  const measured = await page.$$eval('#path-colour option', (o) => o.map((e) => e.value));
  check(measured.includes('measured'), label + ': the tool path can be coloured by the measured peaks');
  if (measured.includes('measured')) {
    await page.select('#path-colour', 'measured');
    await page.$eval('#path-canvas', (e) => e.scrollIntoView({ block: 'center' }));
    await page.screenshot({ path: path.join(args.shots, label + '-by-measured.png') });
    console.log('screenshot: ' + path.join(args.shots, label + '-by-measured.png'));
  }
  finish(opened);
  await page.close();
}

async function checkComparison(browser) {
  const opened = await open(browser, args.comparison, 'comparison');
  const { page } = opened;
  const expected = JSON.parse(fs.readFileSync(args['compare-json'], 'utf8')).rows;
  const names = await page.$$eval('#comparison-table tr td:nth-child(2)', (c) => c.map((e) => e.textContent));
  check(names.length === expected.length && names.every((n, k) => n === expected[k].name),
        'comparison: one table row per strategy, in order (' + names.join(' | ') + ')');
  await chartsPresent(page, ['chart-max_peak_n', 'chart-cycle_time_s'], 'comparison');
  await shot(page, 'comparison');
  finish(opened);
  await page.close();
}

const browser = await puppeteer.launch({
  executablePath: args.chromium,
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--allow-file-access-from-files'],
});
try {
  if (args.plan) await checkPlan(browser);
  if (args.report) await checkReport(browser);
  if (args.history) await checkHistory(browser, args.history, Number(args.cycles), 'history');
  if (args.learn) await checkHistory(browser, args.learn, Number(args['learn-cycles']), 'learn');
  if (args.comparison) await checkComparison(browser);
} finally {
  await browser.close();
}
if (failures.length > 0) {
  console.log('\n' + failures.length + ' check(s) failed:\n  ' + failures.join('\n  '));
  process.exit(1);
}
console.log('\nevery check passed');
