// End-to-end tests of the viewer in headless Chromium, against the real `upkie-rl` binary
// (UPKIE_RL_CLI): a live rollout, a served replay, and a self-contained replay offline.
// Screenshots go to UPKIE_RL_SCREENSHOTS (default: a temporary folder).
import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, mkdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { run, serve } from './cli.mjs';
import { launchBrowser, openViewer, regionDifference, robotBox, screenshotPng } from './browser.mjs';
import { PNG } from 'pngjs';

const work = mkdtempSync(join(tmpdir(), 'upkie-viewer-test-'));
const screenshots = process.env.UPKIE_RL_SCREENSHOTS ?? join(work, 'screenshots');
mkdirSync(screenshots, { recursive: true });

// A pendulum that starts tilted and rolls to catch itself: the base moves.
const ROLLOUT = ['rollout', '--env', 'Upkie-Bullet-Pendulum', '--controller', 'linear:10,1,0,0.1',
  '--env-option', 'init_rand_pitch=0.15', '--seed', '3'];

async function save(page, name) {
  const png = await screenshotPng(page);
  writeFileSync(join(screenshots, name), PNG.sync.write(png));
  return png;
}

/** The robot's screen box, grown by a margin so that a moving robot stays inside. */
async function box(page, margin = 40) {
  const found = await robotBox(page);
  assert.ok(found, 'the robot is on screen');
  return { x: found.x - margin, y: found.y - margin, width: found.width + 2 * margin, height: found.height + 2 * margin };
}

function union(a, b) {
  const x = Math.min(a.x, b.x);
  const y = Math.min(a.y, b.y);
  return { x, y, width: Math.max(a.x + a.width, b.x + b.width) - x, height: Math.max(a.y + a.height, b.y + b.height) - y };
}

const lastFrame = (page) => page.evaluate(() => window.upkieViewer.lastFrame);

let browser;
let record;
before(async () => {
  browser = await launchBrowser();
  record = join(work, 'episodes.csv');
  await run([...ROLLOUT, '--episodes', '2', '--record', record]);
});
after(async () => { await browser?.close(); });

describe('live rollout', () => {
  test('draws the robot and follows the simulation; closing the browser never stops the run', async () => {
    const { child, url, exited } = await serve([...ROLLOUT, '--episodes', '12', '--view', '--view-port', '0', '--view-wait', '1']);
    try {
      const { page, errors } = await openViewer(browser, `${url}?follow=0`);
      await page.waitForFunction(() => window.upkieViewer.framesReceived > 20, null, { timeout: 20000 });
      const first = await lastFrame(page);
      const boxA = await box(page);
      const a = await save(page, 'live.png');
      await page.waitForTimeout(600);
      const second = await lastFrame(page);
      const b = await save(page, 'live_later.png');
      const boxB = await box(page);
      assert.ok(second.time > first.time || second.episode > first.episode, 'frames keep coming');
      assert.equal((await page.evaluate(() => window.upkieViewer.mode)), 'live');
      // The robot moved between the two screenshots, and the pixels show it.
      assert.notDeepEqual([first.base_x, first.pitch], [second.base_x, second.pitch]);
      const moved = regionDifference(a, b, union(boxA, boxB));
      assert.ok(moved > 100, `pixels changed where the robot moves: ${moved}`);

      const empty = await openViewer(browser, `${url}?follow=0&robot=0`);
      const c = await save(empty.page, 'live_empty.png');
      const drawn = regionDifference(b, c, boxB);
      assert.ok(drawn > 500, `pixels where the robot stands differ from the empty scene: ${drawn}`);
      assert.deepEqual(errors, []);
      assert.deepEqual(empty.errors, []);
      await empty.page.context().close();
      await page.context().close();  // the browser goes away mid-run
      const { code, output } = await exited;
      assert.equal(code, 0, output);
      assert.match(output, /mean return .* over 12 episodes/);
    } finally {
      child.kill('SIGKILL');
    }
  });
});

describe('replay', () => {
  test('a served record file replays with its controls', async () => {
    const { child, url, exited } = await serve(['view', record, '--view-port', '0']);
    try {
      const early = await openViewer(browser, `${url}?autoplay=0&t=0.05&follow=0`);
      const late = await openViewer(browser, `${url}?autoplay=0&t=1.2&follow=0`);
      const empty = await openViewer(browser, `${url}?autoplay=0&t=1.2&follow=0&robot=0`);
      assert.equal(await early.page.evaluate(() => window.upkieViewer.mode), 'replay');
      const a = await save(early.page, 'replay.png');
      const b = await save(late.page, 'replay_later.png');
      const c = await save(empty.page, 'replay_empty.png');
      const boxA = await box(early.page);
      const boxB = await box(late.page);
      const frameA = await lastFrame(early.page);
      const frameB = await lastFrame(late.page);
      assert.ok(Math.abs(frameA.time - 0.05) < 0.01 && Math.abs(frameB.time - 1.2) < 0.01,
        `the replays are at the times asked: ${frameA.time}, ${frameB.time}`);
      assert.ok(regionDifference(a, b, union(boxA, boxB)) > 100, 'the pose differs at the two times');
      assert.ok(regionDifference(b, c, boxB) > 500, 'the robot is drawn');
      // Playing moves time forward.
      const played = await openViewer(browser, `${url}?follow=0`);
      await played.page.waitForFunction(() => window.upkieViewer.lastFrame?.time > 0.3, null, { timeout: 10000 });
      for (const view of [early, late, empty, played]) {
        assert.deepEqual(view.errors, []);
        await view.page.context().close();
      }
    } finally {
      child.kill('SIGTERM');
      const { code } = await exited;
      assert.equal(code, 0, 'Ctrl-C (SIGTERM) stops the viewer cleanly');
    }
  });

  test('the camera stays above the floor whatever the mouse does', async () => {
    const html = join(work, 'camera.html');
    await run(['view', record, '--html', html]);
    const { page, errors } = await openViewer(browser, `${pathToFileURL(html).href}?follow=0&autoplay=0`, { offline: true });
    const canvas = await page.$('#scene');
    const rect = await canvas.boundingBox();
    const [x, y] = [rect.x + rect.width / 2, rect.y + rect.height / 2];
    const lowest = [];
    // Orbit (left button) and pan (right button) the eye downwards, far past the floor.
    for (const button of ['left', 'right']) {
      for (let drag = 0; drag < 3; drag++) {
        await page.mouse.move(x, y - 150);
        await page.mouse.down({ button });
        await page.mouse.move(x, y + 250, { steps: 20 });
        await page.mouse.up({ button });
        await page.waitForTimeout(300);  // the damped motion settles
        lowest.push(await page.evaluate(() => window.upkieViewer.cameraHeight()));
      }
    }
    for (const height of lowest) assert.ok(height >= 0.049, `camera height ${height} m: ${lowest}`);
    assert.deepEqual(errors, []);
    await page.context().close();
  });

  test('the self-contained page replays with the network off', async () => {
    const html = join(work, 'replay.html');
    await run(['view', record, '--html', html]);
    const url = pathToFileURL(html).href;
    const { page, errors, requests } = await openViewer(browser, `${url}?follow=0`, { offline: true });
    await page.waitForFunction(() => window.upkieViewer.lastFrame?.time > 0.3, null, { timeout: 10000 });
    const a = await save(page, 'html_replay.png');
    const empty = await openViewer(browser, `${url}?follow=0&robot=0&autoplay=0`, { offline: true });
    const played = await page.evaluate(() => window.upkieViewer.framesDrawn);
    assert.ok(played > 10, `frames drawn offline: ${played}`);
    const b = await save(empty.page, 'html_replay_empty.png');
    assert.ok(regionDifference(a, b, await box(page)) > 500, 'the robot is drawn offline');
    assert.deepEqual(requests, [], 'no request leaves the file');
    assert.deepEqual(errors, []);
    assert.deepEqual(empty.errors, []);
    await page.context().close();
    await empty.page.context().close();
  });
});
