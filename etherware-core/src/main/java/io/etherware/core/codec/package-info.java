/**
 * The XML wire format of {@link io.etherware.core.message.Message}: {@link
 * io.etherware.core.codec.MessageCodec} encodes and decodes it, hardened against hostile input;
 * {@code etherware-message.xsd} (a resource of this package) describes the envelope for peers in
 * other languages.
 */
package io.etherware.core.codec;
