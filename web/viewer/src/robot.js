// The robot from the session's URDF. Its links are primitives without materials, drawn from
// the collision shapes (the URDF has no visuals), coloured by link name.
import * as THREE from 'three';
import URDFLoader from 'urdf-loader';

const material = (color, roughness = 0.6, metalness = 0.1) =>
  new THREE.MeshStandardMaterial({ color, roughness, metalness });

const MATERIALS = {
  tire: material(0x1c1e21, 0.9, 0),
  motor: material(0x555b63, 0.5, 0.2),
  body: material(0xe8822e, 0.55, 0.05),
  other: material(0xc9cdd3, 0.5, 0.3),
};

function materialFor(linkName) {
  if (/wheel|tire/.test(linkName)) return MATERIALS.tire;
  if (/qdd100|mj5208|stator/.test(linkName)) return MATERIALS.motor;
  if (/^(base|torso|battery)$/.test(linkName)) return MATERIALS.body;
  return MATERIALS.other;
}

export function createRobot(urdf) {
  const loader = new URDFLoader();
  loader.parseVisual = true;
  loader.parseCollision = true;
  const robot = loader.parse(urdf);
  for (const link of Object.values(robot.links)) {
    const linkMaterial = materialFor(link.name);
    // Only this link's own shapes: child links hang below their joints.
    for (const child of link.children) {
      if (!child.isURDFCollider && !child.isURDFVisual) continue;
      child.traverse((object) => {
        if (!object.isMesh) return;
        object.material = linkMaterial;
        object.castShadow = true;
        object.receiveShadow = true;
      });
    }
  }
  return robot;
}

/** Puts the robot in the pose of the frame row at `offset` of `data`. */
export function poseRobot(robot, layout, data, offset) {
  const get = (name) => layout.get(data, offset, name);
  robot.position.set(get('base_x'), get('base_y'), get('base_z'));
  robot.quaternion.set(get('base_qx'), get('base_qy'), get('base_qz'), get('base_qw'));
  for (const [name, index] of layout.joints) {
    robot.setJointValue(name, data[offset + index]);
  }
}
