// End-to-end tests of `upkie-rl drive` in headless Chromium: a page drives the MuJoCo
// velocity task balanced by the classical baseline (`lqr`, no trained model) with keys and a
// scripted gamepad; a second page is refused; closing the driving page zeroes the command;
// malformed and out-of-range messages are refused while the run goes on. The measured
// motion is read back from the run's record file.
import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import WebSocket from 'ws';
import { serve } from './cli.mjs';
import { launchBrowser, openViewer, robotBox } from './browser.mjs';

const work = mkdtempSync(join(tmpdir(), 'upkie-drive-test-'));
let runs = 0;

/** Starts a drive recording into a fresh file. */
async function startDrive() {
  runs += 1;
  const record = join(work, `drive${runs}.csv`);
  const served = await serve(['drive', '--env', 'Upkie-MuJoCo-Velocity', '--controller', 'lqr',
    '--view-port', '0', '--record', record]);
  return { ...served, record };
}

/** Stops the drive (SIGTERM, as Ctrl-C) and returns its record as {t, episode, ...} rows. */
async function stopDrive({ child, exited, record }) {
  child.kill('SIGTERM');
  const { code, output } = await exited;
  assert.equal(code, 0, output);
  const [header, ...lines] = readFileSync(record, 'utf8').trim().split('\n');
  const names = header.split(',');
  const rows = lines.map((line) => {
    const values = line.split(',').map(Number);
    return Object.fromEntries(names.map((name, i) => [name, values[i]]));
  });
  return { rows, output };
}

const yawOf = (row) => Math.atan2(2 * (row.base_qw * row.base_qz + row.base_qx * row.base_qy),
  1 - 2 * (row.base_qy ** 2 + row.base_qz ** 2));

/** Rows whose command matches `predicate`, with where the robot went meanwhile. */
function phase(rows, predicate) {
  const selected = rows.filter(predicate);
  assert.ok(selected.length > 0, 'the command reached the simulation');
  const first = selected[0];
  // Until the robot settles: the rows of the phase plus half a second.
  const last = rows[Math.min(rows.indexOf(selected[selected.length - 1]) + 25, rows.length - 1)];
  const heading = yawOf(first);
  const dx = last.base_x - first.base_x;
  const dy = last.base_y - first.base_y;
  return {
    rows: selected,
    forward: dx * Math.cos(heading) + dy * Math.sin(heading),
    yaw: Math.atan2(Math.sin(yawOf(last) - heading), Math.cos(yawOf(last) - heading)),
  };
}

const driveState = (page) => page.evaluate(() => window.upkieViewer.drive);
const waitForRole = (page, role) => page.waitForFunction((wanted) => window.upkieViewer.drive?.role === wanted,
  role, { timeout: 10000 });

async function hold(page, key, milliseconds) {
  await page.keyboard.down(key);
  await page.waitForTimeout(milliseconds);
  await page.keyboard.up(key);
}

// Small pages: software WebGL takes 0.2-0.4 s per frame at 1024x640, and a key event waits
// for the frame under way (a browser with a GPU draws in milliseconds).
const SMALL = { width: 240, height: 160 };

let browser;
before(async () => { browser = await launchBrowser(); });
after(async () => { await browser?.close(); });

describe('drive', () => {
  test('keys drive forward and turn, B and a click push, and the page measures its latency', async () => {
    const drive = await startDrive();
    const { page, errors } = await openViewer(browser, `${drive.url}?plots=0`, SMALL);
    await waitForRole(page, 'free');
    await hold(page, 'KeyA', 1200);
    await page.waitForTimeout(300);
    await hold(page, 'ArrowUp', 600);
    await page.waitForTimeout(600);
    // Pushes: B, then a click on the robot (away from the camera).
    await page.keyboard.press('KeyB');
    const robot = await robotBox(page);
    assert.ok(robot, 'the robot is on screen');
    // The upper quarter of the robot's screen box is its body; the box's centre can fall
    // between the legs, where a click hits nothing (seen once in a clean-clone run).
    await page.mouse.click(robot.x + robot.width / 2, robot.y + robot.height / 4);
    await page.waitForTimeout(300);
    const state = await driveState(page);
    assert.equal(state.role, 'driver');
    assert.deepEqual(errors, []);
    await page.context().close();
    const { rows, output } = await stopDrive(drive);
    assert.equal(output.match(/push: 30 N for 0.2 s/g)?.length, 2, output);
    const forward = phase(rows, (row) => row['command.forward_velocity'] === 0.5);
    const turn = phase(rows, (row) => row['command.yaw_rate'] === 0.75);
    assert.ok(forward.forward > 0.05, `the base moved forward: ${forward.forward} m`);
    assert.ok(turn.yaw > 0.3, `the base turned left: ${turn.yaw} rad`);
    // Key press to "applied" (the command is in the observation the controller acts on), as
    // the page measures it: here it includes the wait for the software renderer's frame.
    const latencies = state.latencies;
    assert.ok(latencies.length >= 4 && latencies.every((l) => l > 0), `latencies measured: ${latencies}`);
    console.log(`key press to applied, headless page [ms]: ${latencies.map((l) => l.toFixed(1)).join(', ')}`);
  });

  test('Z lowers and Q raises the base (height command)', async () => {
    const drive = await startDrive();
    const { page, errors } = await openViewer(browser, `${drive.url}?plots=0`, SMALL);
    await waitForRole(page, 'free');
    for (let press = 0; press < 5; press += 1) await page.keyboard.press('KeyZ');
    await page.waitForTimeout(2500);
    await page.keyboard.press('KeyQ');
    await page.waitForTimeout(1000);
    const state = await driveState(page);
    assert.equal(state.role, 'driver');
    assert.equal(state.height, 0.6, 'five steps down, one up: 0.6 of the height range');
    assert.deepEqual(errors, []);
    await page.context().close();
    const { rows } = await stopDrive(drive);
    const standing = rows[0]['command.height'];
    const lowest = Math.min(...rows.map((row) => row['command.height']));
    // Five tenths of the default range (0.53-0.557 m) below standing.
    assert.ok(Math.abs(standing - lowest - 0.5 * (0.557 - 0.53)) < 1e-6, `commanded ${lowest} m`);
    const crouched = rows.filter((row) => row['command.height'] === lowest);
    assert.ok(crouched.length > 0, 'the crouch reached the simulation');
    const settled = crouched[crouched.length - 1];
    const start = rows.find((row) => row.t > 0.5);
    assert.ok(start.base_z - settled.base_z > 0.01,
      `the base went down: ${start.base_z} m to ${settled.base_z} m`);
  });

  test('the page lists its keys, counts its frames truly and draws legible, moving charts', async () => {
    const drive = await startDrive();
    const { page, errors } = await openViewer(browser, drive.url, { width: 640, height: 400 });
    // The key legend, from the tables the key handlers read.
    const legend = await page.evaluate(() => [...document.querySelectorAll('.hud-keys dt, .hud-keys dd')]
      .map((node) => node.textContent));
    for (const entry of ['↑ / W', 'forward', '← / A', 'turn left', 'R', 'reset', 'P', 'pause', 'B / Shift+B', 'Q', 'raise the base (with a height command)']) {
      assert.ok(legend.includes(entry), `the legend lists "${entry}": ${legend}`);
    }
    assert.ok(await page.evaluate(() => !document.querySelector('.hud-keys').hidden), 'the legend shows');
    // Drive, so that the baseline's actions move.
    await hold(page, 'KeyW', 1500);
    await hold(page, 'KeyA', 800);
    await page.waitForTimeout(1500);
    const status = await page.evaluate(() => document.querySelector('.hud-status').textContent);
    const received = await page.evaluate(() => window.upkieViewer.framesReceived);
    const rate = Number(status.match(/^live: (\d+) frames\/s/)?.[1]);
    // The drive streams its 50 Hz steps in real time (the headless page may lag a little).
    assert.ok(received > 100 && rate >= 20 && rate <= 80, `${status} with ${received} frames received`);
    const charts = await page.evaluate(() => window.upkieViewer.plots());
    for (const chart of charts) {
      for (const ticks of [chart.timeTicks, chart.valueTicks]) {
        const shown = ticks.filter((label) => label !== '');
        assert.ok(shown.length >= 2, `${chart.title}: ticks ${ticks}`);
        assert.equal(new Set(shown).size, shown.length, `${chart.title}: two equal ticks in ${ticks}`);
      }
    }
    for (const chart of charts) {
      assert.ok(chart.plotArea >= 59, `${chart.title}: its curves get ${chart.plotArea} px`);
    }
    const actions = charts.find((chart) => chart.title === 'Actions');
    assert.ok(actions, `an actions chart: ${charts.map((chart) => chart.title)}`);
    const moving = actions.series.filter(({ min, max }) => max - min > 0.01);
    assert.ok(moving.length >= 2, `the wheels' actions move: ${JSON.stringify(actions.series)}`);
    assert.deepEqual(errors, []);
    await page.context().close();
    await stopDrive(drive);
  });

  test('a scripted gamepad drives, pauses, pushes and resets', async () => {
    const drive = await startDrive();
    const { page, errors } = await openViewer(browser, `${drive.url}?plots=0`, SMALL);
    await waitForRole(page, 'free');
    const pad = (axes, buttons = []) => page.evaluate(([a, b]) => {
      window.upkieViewer.drive.testGamepad = { axes: a, buttons: b.map((pressed) => ({ pressed })) };
    }, [axes, buttons]);
    // A button pressed, held until the page polled it, then released.
    const press = async (index) => {
      await pad([0, 0, 0, 0], Array.from({ length: 10 }, (_, i) => i === index));
      await page.waitForTimeout(300);
      await pad([0, 0, 0, 0]);
      await page.waitForTimeout(300);
    };
    await pad([0, 0, 0.5, 0]);  // right stick half right: turn right
    await page.waitForTimeout(1200);
    await pad([0, 0, 0, 0]);
    await page.waitForTimeout(300);
    await pad([0, -0.5, 0, 0]);  // left stick half up
    await page.waitForTimeout(600);
    await pad([0, 0, 0, 0]);
    await page.waitForTimeout(600);
    await press(9);  // Start: pause
    await page.waitForFunction(() => window.upkieViewer.drive.paused, null, { timeout: 5000 });
    await page.waitForTimeout(200);  // the frames sent before the pause
    const pausedAt = (await page.evaluate(() => window.upkieViewer.lastFrame)).time;
    await page.waitForTimeout(400);
    assert.equal((await page.evaluate(() => window.upkieViewer.lastFrame)).time, pausedAt, 'paused');
    await press(9);  // resume
    await page.waitForFunction(() => !window.upkieViewer.drive.paused, null, { timeout: 5000 });
    await press(0);  // A: push
    const episode = await page.evaluate(() => window.upkieViewer.episode);
    await press(8);  // Back: reset
    await page.waitForFunction((before) => window.upkieViewer.episode > before, episode, { timeout: 5000 });
    assert.deepEqual(errors, []);
    await page.context().close();
    const { rows, output } = await stopDrive(drive);
    const forward = phase(rows, (row) => row['command.forward_velocity'] === 0.5);
    const turn = phase(rows, (row) => row['command.yaw_rate'] === -0.75);
    assert.ok(forward.forward > 0.05, `the base moved forward: ${forward.forward} m`);
    assert.ok(turn.yaw < -0.3, `the base turned right: ${turn.yaw} rad`);
    assert.match(output, /push: 30 N for 0.2 s/);
    assert.ok(rows.some((row) => row.episode === episode + 1), 'the reset started a new episode');
  });

  test('a second page watches and is refused; closing the driving page zeroes the command', async () => {
    const drive = await startDrive();
    const driver = await openViewer(browser, `${drive.url}?plots=0`, SMALL);
    const watcher = await openViewer(browser, `${drive.url}?plots=0`, SMALL);
    await driver.page.keyboard.down('ArrowUp');
    await waitForRole(driver.page, 'driver');
    await waitForRole(watcher.page, 'watcher');
    await hold(watcher.page, 'ArrowDown', 300);
    await watcher.page.waitForFunction(() => window.upkieViewer.drive.refusals.length > 0, null, { timeout: 5000 });
    const refusal = (await driveState(watcher.page)).refusals[0].reason;
    assert.match(refusal, /another page drives/);
    // Each change is sent once (press, release), not again at every 20 ms tick while the
    // other page drives.
    const watcherSent = (await driveState(watcher.page)).sent;
    assert.ok(watcherSent <= 3, `the watcher sent ${watcherSent} messages for one key press`);
    // The driving page goes away with its key still held.
    await driver.page.context().close();
    await waitForRole(watcher.page, 'free');
    // The followed command ramps down at the task's 1 m/s² (command_max_acceleration): 0.5 s.
    await watcher.page.waitForTimeout(900);
    assert.deepEqual(watcher.errors, []);
    await watcher.page.context().close();
    const { rows, output } = await stopDrive(drive);
    assert.ok(rows.every((row) => row['command.forward_velocity'] >= 0), 'the watcher never drove');
    const lastDriven = rows.findLastIndex((row) => row['command.forward_velocity'] === 0.5);
    assert.ok(lastDriven > 0, 'the driver drove');
    const after = rows.slice(lastDriven + 1);
    const falling = after.every((row, i) => row['command.yaw_rate'] === 0
      && row['command.forward_velocity'] < 0.5
      && (i === 0 || row['command.forward_velocity'] <= after[i - 1]['command.forward_velocity']));
    assert.ok(falling && after.length > 30
      && after.slice(-5).every((row) => row['command.forward_velocity'] === 0),
      'zero after the driver closed (ramped down)');
    assert.match(output, /commands: \d+ accepted, [1-9]\d* refused/);
  });

  test('a command reaches the simulation within two agent steps (loopback, no rendering)', async () => {
    const drive = await startDrive();
    const socket = new WebSocket(`${drive.url.replace('http', 'ws')}frames`);
    const sentAt = new Map();
    const latencies = [];
    socket.on('message', (data, binary) => {
      if (binary) return;
      const message = JSON.parse(data.toString());
      if (message.type === 'applied' && sentAt.has(message.seq)) {
        latencies.push(performance.now() - sentAt.get(message.seq));
      }
    });
    await new Promise((resolve) => socket.on('open', resolve));
    for (let seq = 1; seq <= 30; seq++) {
      sentAt.set(seq, performance.now());
      socket.send(JSON.stringify({ type: 'command', seq, forward_velocity: 0, yaw_rate: (seq % 2) * 0.1 }));
      // Not a multiple of the 20 ms step: the sends fall anywhere within a step.
      await new Promise((resolve) => setTimeout(resolve, 47));
    }
    socket.close();
    const { output } = await stopDrive(drive);
    latencies.sort((a, b) => a - b);
    const median = latencies[Math.floor(latencies.length / 2)];
    console.log(`send to applied over loopback [ms]: median ${median.toFixed(1)}, max ${latencies[latencies.length - 1].toFixed(1)}; ${output.match(/command latency.*/)?.[0]}`);
    assert.equal(latencies.length, 30, 'every command was acknowledged');
    assert.ok(median < 40, `median within two 20 ms steps: ${latencies}`);
  });

  test('malformed, out-of-range and flooding messages are refused without disturbing the run', async () => {
    const drive = await startDrive();
    const socket = new WebSocket(`${drive.url.replace('http', 'ws')}frames`);
    const texts = [];
    let frames = 0;
    socket.on('message', (data, binary) => { if (binary) frames += 1; else texts.push(JSON.parse(data.toString())); });
    await new Promise((resolve) => socket.on('open', resolve));
    const send = (value) => socket.send(typeof value === 'string' ? value : JSON.stringify(value));
    send({ type: 'command', seq: 1, forward_velocity: 0.2, yaw_rate: 0 });
    const bad = [
      'not json', '[1]', '{"type":"fly"}',
      '{"type":"command","seq":2,"forward_velocity":1e999,"yaw_rate":0}',
      { type: 'command', seq: 3, forward_velocity: null, yaw_rate: 0 },
      { type: 'command', seq: 4, forward_velocity: 5, yaw_rate: 0 },
      { type: 'command', seq: 5, forward_velocity: 0, yaw_rate: -9 },
      { type: 'command', seq: 6.5, forward_velocity: 0, yaw_rate: 0 },
    ];
    for (const message of bad) send(message);
    await new Promise((resolve) => setTimeout(resolve, 300));
    const refusals = texts.filter((text) => text.type === 'refused');
    assert.equal(refusals.length, bad.length, JSON.stringify(texts));
    // A flood: far beyond the rate limit, told once.
    for (let i = 0; i < 500; i++) send({ type: 'command', seq: 100 + i, forward_velocity: 0.2, yaw_rate: 0 });
    await new Promise((resolve) => setTimeout(resolve, 500));
    assert.ok(texts.some((text) => text.type === 'refused' && /too many messages/.test(text.reason)));
    const framesBefore = frames;
    await new Promise((resolve) => setTimeout(resolve, 500));
    assert.ok(frames > framesBefore, 'frames keep coming');
    socket.close();
    const { rows, output } = await stopDrive(drive);
    // Observations are float32: 0.2 reads back as 0.200000003.
    assert.ok(rows.some((row) => Math.abs(row['command.forward_velocity'] - 0.2) < 1e-6), 'the valid command applied');
    assert.ok(rows.every((row) => Math.abs(row['command.forward_velocity']) <= 1
      && Math.abs(row['command.yaw_rate']) <= 1.5), 'no refused value reached the simulation');
    assert.ok(rows.every((row) => row.episode === 0), 'no fall, no reset');
    assert.match(output, /[1-9]\d* over the rate limit/);
  });
});
