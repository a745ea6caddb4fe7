// Opens one HTML report in headless Chromium and prints the milliseconds from navigation until the page
// has drawn everything (window.feedplanReport.ready), then the same for a hover on the tool path and a
// zoom of the charts. Exits 1 on a console error. Used by report_open_bench.
//
// node open_report.mjs WEB_DIR CHROMIUM REPORT.html
import { createRequire } from 'node:module';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [webDir, chromium, file] = process.argv.slice(2);
const require = createRequire(path.resolve(webDir, 'package.json'));
const puppeteer = require('puppeteer-core');
const browser = await puppeteer.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'] });
const errors = [];
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1400, height: 900 });
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  const started = performance.now();
  await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load', timeout: 120000 });
  await page.waitForFunction(() => window.feedplanReport && window.feedplanReport.ready, { timeout: 120000, polling: 10 });
  const opened = performance.now() - started;
  const interaction = await page.evaluate(() => {
    const r = window.feedplanReport;
    const t0 = performance.now();
    r.showSample(Math.floor(r.sampleCount() / 2));
    const t1 = performance.now();
    const s = r.charts['chart-feed'].data[0];
    r.setView([s[0] + 0.4 * (s[s.length - 1] - s[0]), s[0] + 0.6 * (s[s.length - 1] - s[0])]);
    const t2 = performance.now();
    return { hover: t1 - t0, zoom: t2 - t1 };
  });
  console.log(JSON.stringify({ open_ms: opened, hover_ms: interaction.hover, zoom_ms: interaction.zoom }));
} finally {
  await browser.close();
}
if (errors.length > 0) {
  console.error('console errors: ' + errors.join('; '));
  process.exit(1);
}
