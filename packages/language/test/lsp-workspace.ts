/** Shared fixture of the editor-service tests: a small multi-file architecture and position helpers. */
import type { LangiumDocument } from 'langium';
import { TYPES } from './helpers.js';

export const ARCHITECTURE: Record<string, string> = {
    'types.contract': TYPES,
    'msa.contract': `import "types.contract";
synchronous module MSA {
    scheduling { C=500us; }
    data flows { out :0 TypeA coordinates; }
}`,
    'msc.contract': `import "types.contract";
synchronous module MSC {
    parameters { TypeA consigne = {2.1, 6.98, 5.34} :0; }
    scheduling { C=1ms; }
    data flows { in :0 TypeA in_coordinates; out :1 TypeB command; }
    event flows { out :1 TypeD failing; }
}`,
    'msd.contract': `import "types.contract";
synchronous module MSD {
    scheduling { C=2ms; }
    data flows { in :2 TypeB order; }
}`,
    'schema.contract': `import "types.contract";
import "msa.contract";
import "msc.contract";
import "msd.contract";
periodic schema cmd(TypeA consigne = {0.0, 0.0, 0.0}) {
    realtime { PERIOD=10ms; CRITICAL_DELAY=8ms; }
    modules { MSA(); MSC(consigne :0); MSD(); }
    scheduling graph { MSA -> MSC; }
    communications { MSA:0 -> MSC:0 * 1; MSC:1 -> MSD:2 * 2; }
}`,
    'sup.contract': `import "types.contract";
import "msc.contract";
import "schema.contract";
supervisor SUP {
    event flows { in :3 TypeD failure; }
    go(TypeA consigne) {
        local { TypeD failure_data; TypeA target = consigne; int count = 3; }
        rules {
            FIRST: [elapsed=1ms] subscribe MSC:1 =* :3; activate schema cmd(consigne = target) [MSC:1(failure_data = failure)]
            SECOND: [endof(FIRST)] compute doit("x", target.k) [started(SECOND)]
        }
    }
}`
};

/** Offset of the `n`-th occurrence of `needle` in a document, plus `delta`. */
export function offsetOf(doc: LangiumDocument, needle: string, delta = 0, n = 1): number {
    const text = doc.textDocument.getText();
    let at = -1;
    for (let i = 0; i < n; i++) {
        at = text.indexOf(needle, at + 1);
        if (at < 0) throw new Error(`'${needle}' #${n} not in ${doc.uri.path}`);
    }
    return at + delta;
}

/** TextDocumentPositionParams at an offset. */
export function positionParams(doc: LangiumDocument, offset: number) {
    return { textDocument: { uri: doc.uri.toString() }, position: doc.textDocument.positionAt(offset) };
}
