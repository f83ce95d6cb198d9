// hex kernel: in progress
