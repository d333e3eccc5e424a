// The 3-D stage: renderer, Z-up world, floor, lights and an orbit camera that can follow
// the robot. Positions passed in and out of this module are in the Z-up world frame.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const BACKGROUND = 0xdfe5ec;
// Initial view: the yaw and pitch of PyBullet's GUI in upkie (45 deg, -30 deg), from 1.6 m
// rather than 1 m so that the whole robot and the floor around it fit beside the HUD.
const CAMERA_DISTANCE = 1.6;
const CAMERA_YAW = THREE.MathUtils.degToRad(45);
const CAMERA_PITCH = THREE.MathUtils.degToRad(-30);
const TARGET_HEIGHT = 0.3;
const FLOOR_SIZE = 200;  // metres, even so that tiles meet at whole metres
// The eye never goes under the floor: orbiting stops short of the horizon seen from the
// target, and after a pan the target and eye are lifted back above these heights [m].
const MAX_POLAR_ANGLE = THREE.MathUtils.degToRad(88);
const MIN_EYE_HEIGHT = 0.05;
// Sun direction from the robot (Z-up), far enough for the shadow camera to hold it.
const SUN_OFFSET = new THREE.Vector3(1.2, -0.8, 3.0);

/** Z-up world vector to three.js' Y-up scene. */
function toScene(x, y, z) {
  return new THREE.Vector3(x, z, -y);
}

/**
 * One metre of floor: 0.1 m minor lines and a 1 m major line, tiled by the floor texture.
 * A texture rather than a GridHelper: long GL lines that pass behind the camera vanish on
 * software renderers (SwiftShader), and a texture also fades smoothly with distance.
 */
function gridTexture(renderer) {
  const size = 1024;
  const canvas = document.createElement('canvas');
  canvas.width = size;
  canvas.height = size;
  const context = canvas.getContext('2d');
  context.fillStyle = '#eef0f3';
  context.fillRect(0, 0, size, size);
  context.fillStyle = '#c9cfd7';
  for (let i = 1; i < 10; i++) {
    const at = Math.round(i * size / 10);
    context.fillRect(at - 1, 0, 3, size);
    context.fillRect(0, at - 1, size, 3);
  }
  // The major line straddles the tile's edges, half on each side.
  context.fillStyle = '#8a94a1';
  context.fillRect(0, 0, 3, size);
  context.fillRect(size - 3, 0, 3, size);
  context.fillRect(0, 0, size, 3);
  context.fillRect(0, size - 3, size, 3);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.wrapS = THREE.RepeatWrapping;
  texture.wrapT = THREE.RepeatWrapping;
  texture.anisotropy = renderer.capabilities.getMaxAnisotropy();
  return texture;
}

function createFloor(renderer) {
  const texture = gridTexture(renderer);
  texture.repeat.set(FLOOR_SIZE, FLOOR_SIZE);
  const floor = new THREE.Mesh(
    new THREE.PlaneGeometry(FLOOR_SIZE, FLOOR_SIZE),
    new THREE.MeshStandardMaterial({ map: texture, roughness: 0.95 }),
  );
  floor.receiveShadow = true;
  return floor;
}

export function createScene(container) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFShadowMap;
  renderer.domElement.id = 'scene';
  container.prepend(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  scene.fog = new THREE.Fog(BACKGROUND, 8, 40);

  // Everything robot-related lives in the Z-up world; the camera stays in three.js' Y-up.
  const world = new THREE.Group();
  world.rotation.x = -Math.PI / 2;
  scene.add(world);

  const floor = createFloor(renderer);
  world.add(floor);

  scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8478, 1.1));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.castShadow = true;
  sun.shadow.mapSize.set(1024, 1024);
  Object.assign(sun.shadow.camera, { left: -1, right: 1, top: 1, bottom: -1, near: 0.5, far: 6 });
  sun.shadow.bias = -0.0005;
  sun.shadow.radius = 3;
  world.add(sun, sun.target);

  const camera = new THREE.PerspectiveCamera(50, 1, 0.01, 200);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = true;
  controls.dampingFactor = 0.15;
  controls.maxPolarAngle = MAX_POLAR_ANGLE;
  controls.minDistance = 0.2;
  controls.maxDistance = 30;
  // Software renderers are slow: draw only when the view or the scene changed.
  let dirty = true;
  controls.addEventListener('change', () => { dirty = true; });

  let followed = null;  // last (x, y) the view was moved to, Z-up

  function resetView(x, y) {
    const target = toScene(x, y, TARGET_HEIGHT);
    const offset = toScene(
      CAMERA_DISTANCE * Math.cos(CAMERA_PITCH) * Math.sin(CAMERA_YAW),
      -CAMERA_DISTANCE * Math.cos(CAMERA_PITCH) * Math.cos(CAMERA_YAW),
      -CAMERA_DISTANCE * Math.sin(CAMERA_PITCH),
    );
    controls.target.copy(target);
    camera.position.copy(target).add(offset);
    controls.update();
    followed = { x, y };
  }

  /**
   * Moves target and camera by the robot's horizontal displacement, so the angle the user
   * chose stays; height is left alone so a fall stays in view.
   */
  function follow(x, y) {
    if (!followed) {
      resetView(x, y);
      return;
    }
    const delta = toScene(x - followed.x, y - followed.y, 0);
    controls.target.add(delta);
    camera.position.add(delta);
    followed = { x, y };
  }

  /** Keeps floor grid and shadow around the robot at (x, y). */
  function centerOn(x, y) {
    // Whole metres keep the grid lines in place while the floor travels with the robot.
    floor.position.set(Math.round(x), Math.round(y), 0);
    sun.target.position.set(x, y, 0.3);
    sun.position.copy(sun.target.position).add(SUN_OFFSET);
  }

  function resize() {
    const { clientWidth: width, clientHeight: height } = container;
    if (width === 0 || height === 0) return;
    renderer.setSize(width, height, false);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    dirty = true;
  }
  new ResizeObserver(resize).observe(container);
  resize();

  /** Lifts target and eye above the floor (a pan can take them below it). */
  function keepAboveFloor() {
    if (controls.target.y < 0) {
      camera.position.y -= controls.target.y;
      controls.target.y = 0;
    }
    if (camera.position.y < MIN_EYE_HEIGHT) camera.position.y = MIN_EYE_HEIGHT;
  }

  function render() {
    controls.update();
    keepAboveFloor();
    if (!dirty) return;
    dirty = false;
    renderer.render(scene, camera);
  }

  /** Screen box (CSS pixels, page coordinates) of an object, clamped to the canvas. */
  function screenBox(object) {
    const box = new THREE.Box3().setFromObject(object);
    const rect = renderer.domElement.getBoundingClientRect();
    let [left, top, right, bottom] = [Infinity, Infinity, -Infinity, -Infinity];
    for (let i = 0; i < 8; i++) {
      const corner = new THREE.Vector3(
        i & 1 ? box.max.x : box.min.x,
        i & 2 ? box.max.y : box.min.y,
        i & 4 ? box.max.z : box.min.z,
      ).project(camera);
      if (corner.z > 1) continue;  // behind the camera
      const px = rect.left + (corner.x + 1) / 2 * rect.width;
      const py = rect.top + (1 - corner.y) / 2 * rect.height;
      left = Math.min(left, px); right = Math.max(right, px);
      top = Math.min(top, py); bottom = Math.max(bottom, py);
    }
    left = Math.max(left, rect.left); top = Math.max(top, rect.top);
    right = Math.min(right, rect.right); bottom = Math.min(bottom, rect.bottom);
    if (!(right > left && bottom > top)) return null;
    const x = Math.floor(left);
    const y = Math.floor(top);
    return { x, y, width: Math.ceil(right) - x, height: Math.ceil(bottom) - y };
  }

  /** The camera's position in the Z-up world, as {x, y, z}. */
  function cameraPosition() {
    return { x: camera.position.x, y: -camera.position.z, z: camera.position.y };
  }

  return {
    world, resetView, follow, centerOn, render, screenBox, cameraPosition,
    canvas: renderer.domElement, invalidate: () => { dirty = true; },
    cameraHeight: () => camera.position.y,
  };
}
