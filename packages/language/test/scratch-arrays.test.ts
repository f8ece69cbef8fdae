import { it } from 'vitest';
import { build } from './helpers.js';
it('scratch', async () => {
    const b = await build({
        'types.contract': `
const int NJOINTS = 6;
const float PI = 3.14;
enum Mode { IDLE, TELEOP, AUTO }
enum Level { OK, WARN, STOP };
datatype Joints { float[NJOINTS] q, bool enabled = true, Mode mode = Mode.AUTO };
datatype Scan { float[180] ranges, float[3][3] rot = {{1,0,0},{0,1,0},{0,0,1}} };
datatype Alarm { Level level, int code };
datatype Bad { float[2] v = {1.0}, Mode m = Mode.FOO, Mode n = Mode, bool b = 1, float[0] z };
const int A = B;
const int B = A;
`,
        'sup.contract': `import "types.contract";
supervisor SUP {
    event flows { in :1 Alarm alarm; in :2 Scan scan; out :3 Mode mode = Mode.IDLE; }
    action() {
        local { Scan s; float r = 0.0; Mode m = Mode.TELEOP; }
        rules {
            FIRST: [SUP:1<alarm.level == Level.STOP>] [ SUP:2<(scan.ranges[90] < 0.3)>(r = scan.ranges[NJOINTS]) ]
            SECOND: [SUP:2<(scan.ranges[180] < 0.3)>] [ SUP:1<(alarm.level < Level.WARN) | (mode == true)> ]
        }
    }
}`
    });
    console.log(b.lines.join('\n'));
});
