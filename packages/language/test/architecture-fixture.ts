/**
 * A small in-memory architecture modelled on the report's example (§8.1), one element per file,
 * for the schema, scheduler and supervisor validation tests. `architecture({...})` returns the
 * base files with some replaced or added; `header(self)` imports every base file but `self`.
 */
import { TYPES } from './helpers.js';

const BASE: Record<string, string> = {
    't.contract': TYPES,
    'msa.contract': 'synchronous module MSA { scheduling { C=500us; } data flows { out :0 TypeA coordinates; } }',
    'msb.contract': 'synchronous module MSB { scheduling { C=500us; } data flows { out :0 TypeA coordinates; } }',
    'msc.contract': `synchronous module MSC {
        parameters { TypeA param = {2.1,6.98,5.34} :0; }
        scheduling { C=1ms; }
        data flows { in :0 TypeA in_coordinates; out :1 TypeB out_coordinates_command; }
        event flows { out :1 TypeD failing_data; }
    }`,
    'msd.contract': 'synchronous module MSD { scheduling { C=1ms; } data flows { in :2 TypeB in_coordinates_command; } }',
    'maa.contract': `asynchronous module MAA {
        parameters { TypeA param = {22.12,6.98,897.34} :0; }
        event flows { in :0 string controlevent; out :0 TypeC message_type_notification; out :2 string connection_status; }
    }`,
    'mab.contract': 'asynchronous module MAB { event flows { in :0 TypeC message_type_notification; out :1 string link_status; } }',
    'sc1.contract': `periodic schema sc1(TypeA consigne = {0.0, 0.0, 0.0}) {
        realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
        modules { MSA (); MSC (consigne:0); MSD (); }
        scheduling graph { MSA -> MSC; MSC -> MSD; }
        communications { MSA:0 -> MSC:0 * 1; MSC:1 -> MSD:2 * 2; }
    }`,
    'ev.contract': `event schema ev(TypeA param = {27.12,0.0,0.04}) {
        modules { MAA (param :0); MAB (); }
        communications { MAA:0 =* MAB:0; }
    }`,
    'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; } }'
};

export const BASE_FILES = Object.keys(BASE);

/**
 * Import tiers: a file imports the files of lower tiers present in the architecture (types <
 * modules < schemas < scheduler configuration < anything else, such as supervisors).
 */
const TIER: Record<string, number> = {
    't.contract': 0, 'msa.contract': 1, 'msb.contract': 1, 'msc.contract': 1, 'msd.contract': 1, 'maa.contract': 1,
    'mab.contract': 1, 'sc1.contract': 2, 'sc2.contract': 2, 'ev.contract': 2, 'ev2.contract': 2, 'sched.contract': 3, 'sched2.contract': 3
};
const tierOf = (file: string) => TIER[file] ?? 99;

/** Imports for `self`: the files of `present` below its tier. */
export function header(self: string, present: string[] = BASE_FILES): string {
    return present.filter((f) => f !== self && tierOf(f) < tierOf(self)).map((f) => `import "${f}";`).join('\n') + '\n';
}

/** The base architecture with files replaced/added (`undefined` removes a file); every file gets its imports. */
export function architecture(changes: Record<string, string | undefined> = {}): Record<string, string> {
    const all = { ...BASE, ...changes };
    const present = Object.keys(all).filter((f) => all[f] !== undefined);
    const files: Record<string, string> = {};
    for (const name of present) files[name] = header(name, present) + all[name];
    return files;
}

export interface SupervisorOptions {
    name?: string;
    params?: string;
    locals?: string;
    ports?: string;
    more?: string;
}

/** A supervisor in the style of the report's SUP, with the given rules in its function `action`. */
export function supervisor(rules: string, options: SupervisorOptions = {}): string {
    return `supervisor ${options.name ?? 'SUP'} {
    event flows {
        ${options.ports ?? 'in :1 TypeC message_received; in :2 string connection_status; in :3 TypeD failure; out :1 string failure_message_type;'}
    }
    action(${options.params ?? 'TypeA consigne'}) {
        local { ${options.locals ?? 'TypeC temp_message; string temp_mess_type; TypeD failure_data; TypeA temp_consigne = consigne;'} }
        rules {
${rules}
        }
    }
    ${options.more ?? ''}
}`;
}
