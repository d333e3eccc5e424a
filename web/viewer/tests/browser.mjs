// Browser helpers for the viewer's end-to-end tests: headless Chromium (software WebGL),
// a page with its errors and network requests recorded, screenshots as pixels.
import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';

export const CHROMIUM = '/usr/bin/chromium';

// Headless, GPU-less and offline: no background traffic; WebGL 2 from ANGLE on SwiftShader
// (Chromium only falls back to it implicitly with a console warning).
export const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--use-gl=angle',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

export function launchBrowser() {
  return chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
}

/**
 * Opens `url` in a new context and waits for window.upkieViewer.ready. `errors` collects
 * page errors and console errors; with `offline`, `requests` collects every request that
 * is not file: or data:.
 */
export async function openViewer(browser, url, { offline = false, width = 1024, height = 640 } = {}) {
  const context = await browser.newContext({ viewport: { width, height } });
  if (offline) await context.setOffline(true);
  const page = await context.newPage();
  const errors = [];
  const requests = [];
  page.on('pageerror', (err) => errors.push(`pageerror: ${err.message}`));
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(`console: ${message.text()}`);
  });
  if (offline) {
    page.on('request', (request) => {
      if (!/^(file|data):/.test(request.url())) requests.push(request.url());
    });
  }
  await page.goto(url);
  try {
    await page.waitForFunction(() => window.upkieViewer && window.upkieViewer.ready, null,
      { timeout: 30000 });
  } catch (err) {
    const hook = await page.evaluate(() => window.upkieViewer?.errors ?? null).catch(() => null);
    throw new Error(`viewer at ${url} not ready after 30 s: ${err.message}\n`
      + `errors: ${JSON.stringify(errors)}\nupkieViewer.errors: ${JSON.stringify(hook)}`);
  }
  return { page, errors, requests };
}

export async function screenshotPng(page) {
  return PNG.sync.read(await page.screenshot());
}

/** Pixels inside `box` whose R, G or B differs by more than 24 between the two images. */
export function regionDifference(pngA, pngB, { x, y, width, height }) {
  if (pngA.width !== pngB.width || pngA.height !== pngB.height) {
    throw new Error('regionDifference: images differ in size');
  }
  const x0 = Math.max(0, Math.floor(x));
  const y0 = Math.max(0, Math.floor(y));
  const x1 = Math.min(pngA.width, Math.ceil(x + width));
  const y1 = Math.min(pngA.height, Math.ceil(y + height));
  let count = 0;
  for (let row = y0; row < y1; row++) {
    for (let col = x0; col < x1; col++) {
      const i = (row * pngA.width + col) * 4;
      if (Math.abs(pngA.data[i] - pngB.data[i]) > 24
        || Math.abs(pngA.data[i + 1] - pngB.data[i + 1]) > 24
        || Math.abs(pngA.data[i + 2] - pngB.data[i + 2]) > 24) {
        count += 1;
      }
    }
  }
  return count;
}

/** The robot's screen box {x, y, width, height} in CSS pixels, or null when off screen. */
export function robotBox(page) {
  return page.evaluate(() => window.upkieViewer.robotScreenBox());
}
