/**
 * The §2.4–2.6 validators on incomplete input: every truncation point of a supervisor, a schema and
 * a scheduler configuration (as while typing) must give diagnostics, never an internal error.
 */
import { EmptyFileSystem } from 'langium';
import { describe, expect, it } from 'vitest';
import { createCactalServices } from '../src/cactal-module.js';
import { architecture, supervisor } from './architecture-fixture.js';
import { build } from './helpers.js';

const SUP = supervisor(`FIRST: [elapsed=1ms]
        subscribe MAA:2 ==* :2; subscribe MAA:0 ==* :1; activate schema ev(param = temp_consigne)
        [MAA:2<connection_status == "disconnected">]
    SECOND: [(MAA:2<(connection_status == "disconnected" & testit("dedede", temp_consigne))> and started(FIRST){infinite})]
        subscribe MSC:1=>:3; activate schema sc1(consigne = temp_consigne); activate supervisor SUP.action()
        [MSC:1(failure_data = failure, temp_mess_type = "commutation")]
    THIRD: [endof(SECOND) or duration(THIRD)=1ms] notify :1(failure_message_type=temp_mess_type) [started(THIRD)]
    RECEPTION: [MAA:0<(temp_message.value.i > 2)>(temp_message=message_received)]
        parameterize MSC(temp_message.value :0); activate critical module MAA; compute doit("x", temp_consigne.k)
        [ORD:1<ord_schema == "sc1">(temp_mess_type = ord_schema)]`);

const SCHEMA = `periodic schema sc1(TypeA consigne = {0.0, 0.0, 0.0}) {
    realtime { PERIOD=10ms; CRITICAL_DELAY=20ms; }
    modules { MSA (); MSC (consigne.i:0, consigne:0); MSD (); MSD (); }
    scheduling graph { MSA -> MSC; MSC -> MSD; MSD -> MSA; }
    communications { MSA:0 -> MSC:0 * 0; MSC:1 -> MSD:2 * 2; MSA:0 -> MSD:2; MSA:0 =* MSC:0; }
}`;

const SCHED = 'scheduler configuration { modules { MSA; MSC; MAA; MSA; } schemas { sc1; ev; sc1; } }';

const CUTS = 12;

/** The text cut at `CUTS` evenly spread positions, plus with a middle slice removed at each. */
function variants(text: string): string[] {
    const out: string[] = [];
    for (let i = 1; i <= CUTS; i++) {
        const at = Math.floor((text.length * i) / (CUTS + 1));
        out.push(text.slice(0, at));
        out.push(text.slice(0, at) + text.slice(at + 7));
    }
    return out;
}

describe('validators on incomplete input', () => {
    const services = createCactalServices(EmptyFileSystem).Cactal;
    for (const [file, text] of [['sup.contract', SUP], ['sc1.contract', SCHEMA], ['sched.contract', SCHED]] as const) {
        it(`${file}: ${2 * CUTS} truncated/sliced versions give no internal error`, async () => {
            let diagnostics = 0;
            for (const variant of variants(text)) {
                const built = await build(architecture({ [file]: variant }), services);
                const internal = built.diagnostics.filter((d) => d.message.startsWith('An error occurred'));
                expect(internal, variant).toEqual([]);
                diagnostics += built.diagnostics.filter((d) => d.severity === 'error').length;
            }
            expect(diagnostics).toBeGreaterThan(2 * CUTS); // every variant is broken somewhere
        }, 30_000);
    }
});
