/**
 * The machinery of the management service: deciding from a message's origin whether a remote node
 * may ask ({@link io.etherware.services.management.internal.AccessControl}), verifying that a plugin
 * jar is signed by a trusted key, loading implementations from the class path or from allowlisted,
 * signed jars, the class loader of a jar, and the two ends of a migration. Not exported.
 */
package io.etherware.services.management.internal;
