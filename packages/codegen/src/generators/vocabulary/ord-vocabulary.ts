import type { Architecture } from '../../model/architecture.js';
import type { ArchitectureIndex } from '../../model/lookup.js';
import type { Priorities } from '../../model/priorities.js';
import { schemaTable } from './schema-table.js';
import { TableBuilder } from './table-builder.js';

/** `ORD_mod/vocabulary.c`: the scheduler configuration as ContractOrdVocabulary tables. */
export function generateOrdVocabulary(arch: Architecture, index: ArchitectureIndex, priorities: Priorities): string {
    // every datatype with its field table: its parameterize actions show values field by field
    // (`parameterize VEL:0 setpoint (16 bytes) = {v=0.3,w=0}`), not `{16 bytes}`
    const b = new TableBuilder(index, { allFieldTables: true });
    const config = arch.scheduler ?? { modules: [], schemas: [] };
    const modules = config.modules.map((m) => `{"${m}", ${priorities.of.get(m) ?? 0}, ${index.modules.get(m)?.wcetNs ?? 0}}`);
    const emitted = new Map<string, string>();
    const schemas = config.schemas.flatMap((s) => {
        const schema = index.schemas.get(s);
        return schema ? [schemaTable(b, schema, emitted)] : [];
    });
    const mods = b.array('ord_modules', 'ContractOrdModule', modules);
    const sch = b.array('ord_schemas', 'ContractSchema *const', schemas);
    const sups = b.array('ord_supervisors', 'char *const', arch.supervisors.map((s) => `"${s.name}"`));
    b.define(`const ContractOrdVocabulary ORD_VOCABULARY = {\n    CONTRACT_VOCABULARY_VERSION, ${modules.length}, ${mods}, ${schemas.length}, ${sch}, ${arch.supervisors.length}, ${sups}};`);
    return b.render([
        '// vocabulary.c of ORD (generated whole from the scheduler configuration; format: contract/vocabulary.h)',
        '#include <stddef.h>',
        '#include <contract/vocabulary.h>',
        '#include "schedtypes.h"',
    ]);
}
