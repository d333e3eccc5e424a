// Entry point: loads the session, builds scene, robot, HUD and plots, and draws the newest
// live frame or the replayed frame at each animation frame. window.upkieViewer is the test
// hook.
import uplotCss from 'uplot/dist/uPlot.min.css';
import viewerCss from './style.css';
import { errors, guard, onError, reportError } from './errors.js';
import { options } from './options.js';
import { FrameLayout, loadSession } from './session.js';
import { createScene } from './scene.js';
import { createRobot, poseRobot } from './robot.js';
import { createHud } from './hud.js';
import { createPlots } from './plots.js';
import { createLiveSource } from './live_source.js';
import { createReplaySource } from './replay_source.js';
import { createReplayBar } from './replay_bar.js';
import { createDrive } from './drive.js';

const style = document.createElement('style');
style.textContent = `${uplotCss}\n${viewerCss}`;
document.head.append(style);

const viewer = {
  ready: false,
  mode: null,
  framesReceived: 0,
  framesDrawn: 0,
  episode: null,
  lastFrame: null,
  connected: false,
  errors,
  robotScreenBox: () => null,
  cameraHeight: () => null,
  drive: null,  // the driving state (upkie-rl drive): role, refusals, latencies, testGamepad
  plots: () => [],  // each chart's title, tick labels last drawn and values' range
};
window.upkieViewer = viewer;

const hud = createHud(document.getElementById('hud'));
onError((message) => hud.showError(message));

/** Yaw of the base [rad] in the frame row at `offset` of `data`. */
function baseYaw(layout, data, offset) {
  const [w, x, y, z] = ['base_qw', 'base_qx', 'base_qy', 'base_qz'].map((name) => layout.get(data, offset, name));
  return Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
}

function start(session) {
  const layout = new FrameLayout(session);
  hud.addCharts(layout.charts);
  viewer.mode = session.mode;
  hud.setTitle(session.title ?? 'Upkie');
  document.title = `${session.title ?? 'Upkie'} · Upkie viewer`;

  const stage = document.getElementById('stage');
  const scene = createScene(stage);
  const robot = createRobot(session.urdf);
  robot.visible = options.robot;
  scene.world.add(robot);
  viewer.robotScreenBox = () => scene.screenBox(robot);
  viewer.cameraHeight = () => scene.cameraHeight();

  const followBox = document.getElementById('follow');
  followBox.checked = options.follow;

  const plotPanel = document.getElementById('plots');
  plotPanel.hidden = !options.plots;
  const plots = createPlots(plotPanel, layout);
  viewer.plots = () => plots.describe();

  // Each source yields the frame row to draw at this animation frame.
  let nextFrame;
  let drawn = null;
  if (session.mode === 'live') {
    let drive = null;
    const live = createLiveSource(session, layout, {
      onMessage: (message) => drive?.onMessage(message),
      onFrames: (data, count, state) => {
        for (let row = 0; row < count; row++) plots.append(data, row * layout.size);
        viewer.framesReceived = state.framesReceived;
      },
      onStatusChange: ([text, kind], state) => {
        viewer.connected = state.connected;
        hud.setStatus(text, kind);
      },
    });
    nextFrame = () => {
      plots.flush();
      return live.latest;
    };
    if (session.drive) {
      drive = createDrive(session, {
        send: (text) => live.send(text),
        hud,
        canvas: scene.canvas,
        robotYaw: () => (drawn ? baseYaw(layout, drawn.data, drawn.offset) : 0),
        // Away from the camera, when the click is on the robot.
        pushDirection: (event) => {
          const box = scene.screenBox(robot);
          const bounds = scene.canvas.getBoundingClientRect();
          const x = event.clientX - bounds.left;
          const y = event.clientY - bounds.top;
          if (!drawn || !box || x < box.x || y < box.y || x > box.x + box.width || y > box.y + box.height) return null;
          const eye = scene.cameraPosition();
          return Math.atan2(layout.get(drawn.data, drawn.offset, 'base_y') - eye.y,
            layout.get(drawn.data, drawn.offset, 'base_x') - eye.x);
        },
      });
      viewer.drive = drive.state;
    }
  } else {
    const replay = createReplaySource(session, layout, options);
    const bar = createReplayBar(document.getElementById('replay-bar'), replay);
    viewer.framesReceived = replay.state.framesReceived;
    hud.setStatus('replay', 'idle');
    let plottedEpisode = -1;
    let lastTime = null;
    nextFrame = (now) => {
      // Long gaps (hidden tab) would jump ahead: count at most a quarter second.
      const elapsed = lastTime === null ? 0 : Math.min((now - lastTime) / 1000, 0.25);
      lastTime = now;
      replay.advance(elapsed);
      const { state } = replay;
      if (state.episodeIndex !== plottedEpisode) {
        plottedEpisode = state.episodeIndex;
        const episode = state.episodes[plottedEpisode];
        plots.showEpisode(episode.data, episode.count);
      }
      plots.mark(state.playTime);
      bar.update();
      return replay.frame();
    };
  }

  let viewPlaced = false;
  // Turning follow back on brings the robot back into view at once, even when paused.
  followBox.addEventListener('change', guard('follow', () => {
    if (!followBox.checked || !drawn) return;
    scene.follow(layout.get(drawn.data, drawn.offset, 'base_x'), layout.get(drawn.data, drawn.offset, 'base_y'));
    scene.invalidate();
  }));
  const draw = guard('draw', (now) => {
    const frame = nextFrame(now);
    if (frame && (frame.data !== drawn?.data || frame.offset !== drawn?.offset)) {
      drawn = frame;
      poseRobot(robot, layout, frame.data, frame.offset);
      const x = layout.get(frame.data, frame.offset, 'base_x');
      const y = layout.get(frame.data, frame.offset, 'base_y');
      if (followBox.checked || !viewPlaced) scene.follow(x, y);
      viewPlaced = true;
      scene.centerOn(x, y);
      scene.invalidate();
      viewer.framesDrawn += 1;
      viewer.lastFrame = layout.toObject(frame.data, frame.offset);
      viewer.episode = viewer.lastFrame.episode;
      hud.show(viewer.lastFrame);
    }
    scene.render();
    if (drawn) viewer.ready = true;
  });
  const loop = (now) => {
    draw(now);
    requestAnimationFrame(loop);
  };
  requestAnimationFrame(loop);
}

loadSession().then(guard('start', start), (err) => {
  reportError(err, 'session');
  hud.setStatus('no session', 'bad');
});
