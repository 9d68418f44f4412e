/** The Notifier: periodic and one-shot Ticks at absolute release times (paper Section III-C). */
package io.etherware.services.notifier;
