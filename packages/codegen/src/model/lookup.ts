import type { Architecture, Datatype, FunctionPrototype, Module, Schema, Supervisor, TypeRef } from './architecture.js';

/** Name-indexed access to an architecture's entities (all names are unique project-wide). */
export class ArchitectureIndex {
    readonly datatypes = new Map<string, Datatype>();
    readonly functions = new Map<string, FunctionPrototype>();
    readonly modules = new Map<string, Module>();
    readonly schemas = new Map<string, Schema>();
    readonly supervisors = new Map<string, Supervisor>();

    constructor(readonly architecture: Architecture) {
        for (const d of architecture.datatypes) this.datatypes.set(d.name, d);
        for (const f of architecture.functions) this.functions.set(f.name, f);
        for (const m of architecture.modules) this.modules.set(m.name, m);
        for (const s of architecture.schemas) this.schemas.set(s.name, s);
        for (const s of architecture.supervisors) this.supervisors.set(s.name, s);
    }

    datatype(name: string): Datatype {
        const d = this.datatypes.get(name);
        if (!d) throw new Error(`unknown datatype '${name}'`);
        return d;
    }

    /** The datatypes a type depends on, itself included, dependencies first. */
    datatypeClosure(type: TypeRef, into: string[] = []): string[] {
        if ('datatype' in type && !into.includes(type.datatype)) {
            for (const f of this.datatype(type.datatype).fields) this.datatypeClosure(f.type, into);
            into.push(type.datatype);
        }
        return into;
    }
}

export function typeName(t: TypeRef): string {
    return 'primitive' in t ? t.primitive : t.datatype;
}

export function isString(t: TypeRef): boolean {
    return 'primitive' in t && t.primitive === 'string';
}
