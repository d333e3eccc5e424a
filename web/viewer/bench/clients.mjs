// Does a live rollout keep its speed with many browsers connected? Runs `upkie-rl rollout
// --view --view-speed 0` (unpaced) with 0 and N WebSocket clients reading every frame, and
// prints the wall time of each run and the frames each client got.
// Usage: node bench/clients.mjs UPKIE_RL_CLI [clients=10] [episodes=100] [repeats=3]
import { spawn } from 'node:child_process';
import WebSocket from 'ws';

const [cli, clientsArg = '10', episodesArg = '100', repeatsArg = '3'] = process.argv.slice(2);
if (!cli) throw new Error('usage: node bench/clients.mjs UPKIE_RL_CLI [clients] [episodes] [repeats]');

function rollout(clients) {
  return new Promise((resolve, reject) => {
    const start = process.hrtime.bigint();
    const child = spawn(cli, ['rollout', '--env', 'Upkie-Bullet-Pendulum', '--controller', 'linear:10,1,0,0.1',
      '--episodes', episodesArg, '--view', '--view-port', '0', '--view-speed', '0', '--view-wait', String(clients)]);
    let output = '';
    const received = [];
    let connected = false;
    child.stdout.on('data', (data) => {
      output += data;
      const match = output.match(/viewer: (http:\/\/\S+)\//);
      if (match && !connected) {
        connected = true;
        for (let i = 0; i < clients; i++) {
          const index = received.push(0) - 1;
          const socket = new WebSocket(`${match[1].replace('http', 'ws')}/frames`);
          socket.binaryType = 'arraybuffer';
          socket.on('message', (data, isBinary) => {
            if (isBinary) received[index] += data.byteLength / (20 * 8);
          });
          socket.on('error', () => {});
        }
      }
    });
    child.on('close', (code) => {
      if (code !== 0) reject(new Error(`rollout exited ${code}: ${output}`));
      resolve({ seconds: Number(process.hrtime.bigint() - start) / 1e9, received });
    });
  });
}

const steps = Number(episodesArg) * 300;
for (const clients of [0, Number(clientsArg)]) {
  for (let repeat = 0; repeat < Number(repeatsArg); repeat++) {
    const { seconds, received } = await rollout(clients);
    const frames = received.length ? `, frames per client ${Math.min(...received)}-${Math.max(...received)}` : '';
    console.log(`${clients} clients: ${seconds.toFixed(2)} s, ${(steps / seconds).toFixed(0)} steps/s${frames}`);
  }
}
