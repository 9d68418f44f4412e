/**
 * The Etherware message: {@link io.etherware.core.message.Message} with its
 * {@link io.etherware.core.message.Profile}, {@link io.etherware.core.message.QoS} and registered
 * {@link io.etherware.core.message.Contents}, as immutable records.
 */
package io.etherware.core.message;
